#!/usr/bin/env bash
# Slats as processes against the loop it replaced, on the same machine in the
# same run.
#
#   bench/pxpl5_slats_bench.sh OLD_LATSIM [NEW_LATSIM] [REPEATS]
#
# Runs scenarios/pxpl5/slats_140.json (10 simulated seconds) with each binary
# in turn, REPEATS times (default 5), and prints per run the simulation-loop
# wall time (summary.json wall_s), the whole command's wall time, the events
# and the pxpl5 model's events, then the medians and their ratio (new / old).
# The load average is printed before and after: the machine may be shared.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
old="$1"
new="${2:-$root/build/latsim}"
repeats="${3:-5}"
work="$(mktemp -d /tmp/latsim_pxpl5_bench.XXXXXX)"
trap 'rm -rf "$work"' EXIT
scenario="$root/scenarios/pxpl5/slats_140.json"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for i in $(seq 1 "$repeats"); do
  for which in old new; do
    bin=$old
    [ "$which" = new ] && bin=$new
    start=$(date +%s.%N)
    "$bin" run "$scenario" --out "$work/$which" -q 2>/dev/null
    end=$(date +%s.%N)
    python3 - "$work/$which/summary.json" "$which" "$start" "$end" >>"$work/rows.txt" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
total = float(sys.argv[4]) - float(sys.argv[3])
print(sys.argv[2], s["wall_s"], total, s["events"], s["events_per_model"].get("pxpl5", 0))
PY
  done
done
echo "load after:  $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$work/rows.txt" <<'PY'
import statistics, sys
rows = [line.split() for line in open(sys.argv[1])]
print("binary  loop_s  command_s  events  pxpl5_events")
for r in rows:
    print(f"{r[0]:<6}  {float(r[1]):.3f}  {float(r[2]):.3f}  {r[3]}  {r[4]}")
med = {w: (statistics.median(float(r[1]) for r in rows if r[0] == w),
           statistics.median(float(r[2]) for r in rows if r[0] == w)) for w in ("old", "new")}
for w in ("old", "new"):
    print(f"median {w}: loop {med[w][0]:.3f} s, command {med[w][1]:.3f} s")
print(f"new / old: loop {med['new'][0] / med['old'][0]:.2f}x, command {med['new'][1] / med['old'][1]:.2f}x")
PY
