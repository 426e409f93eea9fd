#!/usr/bin/env bash
# Threads against processes: one sweep run with each thread count, and the
# same sweep as that many --shard processes at once followed by --collect.
#
#   bench/sweep_scaling.sh [THREADS ...]          (default: 1 2 16)
#   environment: LATSIM=build/latsim  REPLICATIONS=10  WORK=<new temporary directory>  SHARDS=1
#
# The sweep is the 2,000-run shape of BENCHMARKS.md ("A sweep costs what it
# simulates"): scenarios/hmd_60hz_serial_poll.json cut to 1 simulated second,
# display refresh 50..95 Hz (10 values) x host poll interval 1..20 ms (20
# values) x REPLICATIONS (10: 2,000 runs). Every sweep goes into a fresh
# directory, and its results.csv must equal the first one's but for wall_s.
# Prints one table row per thread count: wall and CPU time (user + sys of the
# process), runs per second, the speed-up over the first row and the
# efficiency (speed-up over the first row / its gain in CPUs that can run
# at once: threads beyond the machine's CPUs gain nothing); with
# SHARDS=1 also the wall time of as many --shard processes (-j1 each) and of
# the --collect after them. Needs only a built latsim: nothing is compiled.
# On a 16-core machine the three default rows take about a minute.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
latsim="${LATSIM:-$root/build/latsim}"
replications="${REPLICATIONS:-10}"
shards="${SHARDS:-1}"
threads=("$@")
[ ${#threads[@]} -gt 0 ] || threads=(1 2 16)
work="${WORK:-$(mktemp -d /tmp/latsim_sweep_scaling.XXXXXX)}"
mkdir -p "$work"
runs=$((200 * replications))
cpus=$(nproc)
[ -x "$latsim" ] || { echo "sweep_scaling: no latsim at $latsim (build it first, or set LATSIM)" >&2; exit 2; }

# shellcheck source=bench/sweep_shape.sh
. "$here/sweep_shape.sh"
write_sweep_shape "$work/shape.json" "$replications"

# Runs a command; sets wall, cpu (user + sys, children included).
TIMEFORMAT='%R %U %S'
timed() {
  local t
  t=$( { time "$@" > /dev/null 2> "$work/stderr"; } 2>&1 ) || { cat "$work/stderr" >&2; exit 1; }
  read -r wall user sys <<< "$t"
  cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.2f", u + s }')
}

# results.csv without wall_s, the column that measures the machine.
table() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "wall_s") drop = i } { line = ""; for (i = 1; i <= NF; i++) if (i != drop) line = line $i ","; print line }' "$1/results.csv"
}

# Runs N --shard processes (-j1) at once, then --collect; sets shard_wall, collect_wall.
shard_and_collect() {
  local n=$1 out=$2 start end pids=()
  start=$(date +%s.%N)
  for ((i = 0; i < n; i++)); do
    "$latsim" sweep "$work/shape.json" --out "$out" --shard "$i/$n" -j 1 > /dev/null 2>> "$work/stderr" & pids+=($!)
  done
  for pid in "${pids[@]}"; do wait "$pid" || { cat "$work/stderr" >&2; exit 1; }; done
  end=$(date +%s.%N)
  shard_wall=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }')
  timed "$latsim" sweep "$work/shape.json" --out "$out" --collect
  collect_wall=$wall
}

echo "sweep_scaling: $runs runs of 1 s, $(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg), $("$latsim" --version | head -1)"
printf '| threads | wall (s) | CPU (s) | runs/s | speed-up | efficiency |'
[ "$shards" = 1 ] && printf ' %s |' "shards: wall (s)" "--collect (s)" "collect / shards"
printf '\n|---:|---:|---:|---:|---:|---:|'
[ "$shards" = 1 ] && printf -- '---:|---:|---:|'
printf '\n'
base_wall="" base_threads=""
for t in "${threads[@]}"; do
  out="$work/j$t"
  rm -rf "$out"
  timed "$latsim" sweep "$work/shape.json" --out "$out" -j "$t"
  [ -n "$base_wall" ] || { base_wall=$wall; base_threads=$t; table "$out" > "$work/reference.csv"; }
  table "$out" | cmp -s - "$work/reference.csv" || { echo "sweep_scaling: -j$t results.csv differs from -j$base_threads's" >&2; exit 1; }
  speedup=$(awk -v a="$base_wall" -v b="$wall" 'BEGIN { printf "%.2f", a / b }')
  efficiency=$(awk -v s="$speedup" -v t="$t" -v b="$base_threads" -v c="$cpus" 'BEGIN { m = t < c ? t : c; n = b < c ? b : c; printf "%.0f %%", 100 * s * n / m }')
  rate=$(awk -v n="$runs" -v w="$wall" 'BEGIN { printf "%.0f", n / w }')
  printf '| %s | %.2f | %.2f | %s | %s | %s |' "$t" "$wall" "$cpu" "$rate" "$speedup" "$efficiency"
  if [ "$shards" = 1 ]; then
    rm -rf "$out.shards"
    shard_and_collect "$t" "$out.shards"
    table "$out.shards" | cmp -s - "$work/reference.csv" || { echo "sweep_scaling: $t shards' results.csv differs" >&2; exit 1; }
    ratio=$(awk -v c="$collect_wall" -v s="$shard_wall" 'BEGIN { printf "%.2f", c / s }')
    printf ' %s | %.2f | %s |' "$shard_wall" "$collect_wall" "$ratio"
    rm -rf "$out.shards"
  fi
  printf '\n'
  rm -rf "$out"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg); work directory: $work"
