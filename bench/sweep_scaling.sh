#!/usr/bin/env bash
# Threads against processes: one sweep run with each thread count, then the
# same sweep as N --shard processes at once followed by --collect.
#
#   bench/sweep_scaling.sh [BUILD_DIR] [THREADS ...]     (default: build 1 2 4 8 16)
#   environment: SHARDS="16" (shard counts, each one row; "" for none)
#                REPLICATIONS=10  WORK=<new temporary directory>
#
# Needs only BUILD_DIR/latsim, as `scripts/setup.sh` builds it (Release):
# nothing is compiled here. The sweep is the 2,000-run shape of BENCHMARKS.md
# ("A sweep costs what it simulates", bench/sweep_shape.sh):
# scenarios/hmd_60hz_serial_poll.json cut to 1 simulated second, display
# refresh 50..95 Hz (10 values) x host poll interval 1..20 ms (20 values) x
# REPLICATIONS (10: 2,000 runs). Every sweep goes into a fresh directory and
# its results.csv must equal the first one's but for wall_s.
#
# Prints one table row per thread count and one per shard count: wall and
# CPU time (user + sys, children included), runs per second, the speed-up
# over the first row and the efficiency (speed-up / the gain in CPUs that can
# run at once: threads or shards beyond the machine's CPUs gain nothing); a
# shard row adds the wall time of its --collect and its share of the shards'.
# On a 16-core machine the default rows take well under a minute.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$root/build"
if [ $# -gt 0 ] && [ -d "$1" ]; then build="$(cd "$1" && pwd)"; shift; fi
latsim="$build/latsim"
replications="${REPLICATIONS:-10}"
read -r -a shard_counts <<< "${SHARDS-16}"
threads=("$@")
[ ${#threads[@]} -gt 0 ] || threads=(1 2 4 8 16)
work="${WORK:-$(mktemp -d /tmp/latsim_sweep_scaling.XXXXXX)}"
mkdir -p "$work"
runs=$((200 * replications))
cpus=$(nproc)
[ -x "$latsim" ] || { echo "sweep_scaling: no latsim in $build (run scripts/setup.sh first)" >&2; exit 2; }

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

# N --shard processes (-j1 each) at once; the whole under `time` (so CPU counts them all).
run_shards() {
  local n=$1 out=$2 i pids=() failed=0
  for ((i = 0; i < n; i++)); do
    "$latsim" sweep "$work/shape.json" --out "$out" --shard "$i/$n" -j 1 > /dev/null 2>> "$work/stderr" & pids+=($!)
  done
  for i in "${pids[@]}"; do wait "$i" || failed=1; done
  return $failed
}

base_wall="" base_n=""
# A row's speed-up, efficiency and rate from wall for N threads or processes.
row_figures() {
  local n=$1
  [ -n "$base_wall" ] || { base_wall=$wall; base_n=$n; }
  speedup=$(awk -v a="$base_wall" -v b="$wall" 'BEGIN { printf "%.2f", a / b }')
  efficiency=$(awk -v s="$speedup" -v t="$n" -v b="$base_n" -v c="$cpus" 'BEGIN { m = t < c ? t : c; n = b < c ? b : c; printf "%.0f %%", 100 * s * n / m }')
  rate=$(awk -v n="$runs" -v w="$wall" 'BEGIN { printf "%.0f", n / w }')
}

check_table() {
  table "$1" | cmp -s - "$work/reference.csv" || { echo "sweep_scaling: $2's results.csv differs from the first row's" >&2; exit 1; }
}

start_s=$SECONDS
echo "sweep_scaling: $runs runs of 1 s, $cpus CPUs, load $(cut -d' ' -f1-3 /proc/loadavg), $("$latsim" --version | head -1)"
echo '| sweep | wall (s) | CPU (s) | runs/s | speed-up | efficiency | --collect wall (s) | collect / shards |'
echo '|---|---:|---:|---:|---:|---:|---:|---:|'
for t in "${threads[@]}"; do
  out="$work/j$t"
  rm -rf "$out"
  timed "$latsim" sweep "$work/shape.json" --out "$out" -j "$t"
  [ -f "$work/reference.csv" ] || table "$out" > "$work/reference.csv"
  check_table "$out" "-j$t"
  row_figures "$t"
  printf '| -j%s | %.2f | %.2f | %s | %s | %s | | |\n' "$t" "$wall" "$cpu" "$rate" "$speedup" "$efficiency"
  rm -rf "$out"
done
for n in "${shard_counts[@]}"; do
  out="$work/shards$n"
  rm -rf "$out"
  timed run_shards "$n" "$out"
  shard_wall=$wall shard_cpu=$cpu
  timed "$latsim" sweep "$work/shape.json" --out "$out" --collect
  collect_wall=$wall
  [ -f "$work/reference.csv" ] || table "$out" > "$work/reference.csv"
  check_table "$out" "$n shards"
  wall=$shard_wall cpu=$shard_cpu
  row_figures "$n"
  ratio=$(awk -v c="$collect_wall" -v s="$shard_wall" 'BEGIN { printf "%.2f", c / s }')
  printf '| %s x --shard i/%s -j1 | %.2f | %.2f | %s | %s | %s | %.2f | %s |\n' "$n" "$n" "$wall" "$cpu" "$rate" \
    "$speedup" "$efficiency" "$collect_wall" "$ratio"
  rm -rf "$out"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg); $((SECONDS - start_s)) s in all; work directory: $work"
