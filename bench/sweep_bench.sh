#!/usr/bin/env bash
# Sweep and fidelity benchmarks.
#
#   bench/sweep_bench.sh [LATSIM] [WORK_DIR]
#
# 1. A 1000-run sweep (25 tracker delays x 4 tracker rates x 10 replications) of
#    the 10-simulated-second double-buffered scenario without frames, at -j1
#    and at -j2, each into a fresh directory: wall time, runs/s, speed-up, and
#    whether -j2 finished within the 60 s budget. The two results.csv must be
#    identical apart from the wall_s column.
# 2. `latsim fidelity` on the same scenario over scanout field, line, pixel:
#    events, wall time and peak memory per level, and the error of the mean
#    motion-to-photon latency against per-pixel scanout.
# Exit status 1 when the budget is missed or the two tables differ.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
latsim="${1:-$root/build/latsim}"
work="${2:-$(mktemp -d /tmp/latsim_sweep_bench.XXXXXX)}"
mkdir -p "$work"
base="$root/scenarios/hmd_60hz_direct.json"

cat > "$work/sweep_1000.json" <<EOF
{
  "description": "1000 runs of 10 simulated seconds, double-buffered, no frames",
  "base": "$base",
  "overrides": {"/duration_s": 10},
  "axes": [
    {"pointer": "/tracker/internal_delay_ms", "range": {"from": 0, "to": 24, "step": 1}},
    {"pointer": "/tracker/rate_hz", "values": [30, 60, 120, 240]}
  ],
  "replications": 10,
  "seed": 1
}
EOF

time_sweep() {  # jobs: writes "wall user sys" (seconds) to $work/time_j<jobs>
  local jobs="$1" out="$work/sweep_j$1"
  rm -rf "$out"
  /usr/bin/time -f "%e %U %S" -o "$work/time_j$jobs" \
    "$latsim" sweep "$work/sweep_1000.json" --out "$out" -j "$jobs" > "$work/sweep_j$jobs.log"
}

# The machine may be shared: CPU time (user + sys) shows whether -j2 did more
# work than -j1 or merely got less of the machine.
echo "machine: $(nproc) cores, load before $(cut -d' ' -f1-3 /proc/loadavg)"
time_sweep 1
time_sweep 2
read -r w1 u1 s1 < "$work/time_j1"
read -r w2 u2 s2 < "$work/time_j2"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '1000-run sweep -j1: %.1f s wall (%.1f runs/s), %.1f s CPU\n' "$w1" "$(echo "1000 / $w1" | bc -l)" "$(echo "$u1 + $s1" | bc -l)"
printf '1000-run sweep -j2: %.1f s wall (%.1f runs/s), %.1f s CPU; speed-up %.2fx\n' "$w2" "$(echo "1000 / $w2" | bc -l)" \
  "$(echo "$u2 + $s2" | bc -l)" "$(echo "$w1 / $w2" | bc -l)"
t2="$w2"

status=0
strip_wall() { python3 -c 'import csv,sys
rows=list(csv.reader(open(sys.argv[1])));i=rows[0].index("wall_s")
print("\n".join(",".join(c for j,c in enumerate(r) if j!=i) for r in rows))' "$1"; }
if [ "$(strip_wall "$work/sweep_j1/results.csv")" != "$(strip_wall "$work/sweep_j2/results.csv")" ]; then
  echo "FAIL: results.csv differs between -j1 and -j2"; status=1
fi
if [ "$(echo "$t2 < 60" | bc -l)" != 1 ]; then
  echo "FAIL: the -j2 sweep took longer than 60 s"; status=1
fi

"$latsim" fidelity "$base" --set /duration_s=10 --vary /display/scanout=field,line,pixel \
  --metric motion_to_photon_ms.mean --out "$work/fidelity" 2> "$work/fidelity.log"
echo "work directory: $work"
exit $status
