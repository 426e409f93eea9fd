#!/usr/bin/env bash
# Sweeps at scale: disk and report time of a sweep of many 1 s runs.
#
#   bench/sweep_scale_bench.sh [LATSIM] [REPLICATIONS] [WORK_DIR] [KEEP]
#
# The shape of scenarios/sweeps/refresh_and_poll.json, larger and shorter:
# the polled serial HMD cut to 1 simulated second, display refresh 50..95 Hz
# (10 values) x host poll interval 1..20 ms (20 values) x REPLICATIONS
# (default 10: 2,000 runs; 100: 20,000 runs), tracker jitter 1 ms so that
# replications differ. Runs `latsim sweep -j2 --keep KEEP` (default figures)
# into a fresh directory, then `latsim report` on it (its defaults), and
# prints for each the wall and CPU time, then the directory's size (du -sh),
# the files in it and the bytes per run. Exit status 1 when the report of a
# 2,000-run sweep takes a minute or more or its directory 150 MB or more.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
latsim="${1:-$root/build/latsim}"
replications="${2:-10}"
work="${3:-$(mktemp -d /tmp/latsim_scale_bench.XXXXXX)}"
keep="${4:-figures}"
mkdir -p "$work"
runs=$((200 * replications))

cat > "$work/scale.json" <<EOF
{
  "description": "refresh x poll interval at scale: 10 x 20 points of 1 s runs, $replications replications",
  "base": "$root/scenarios/hmd_60hz_serial_poll.json",
  "overrides": {"/duration_s": 1, "/tracker/jitter_ms": 1},
  "axes": [
    {"pointer": "/display/refresh_hz", "range": {"from": 50, "to": 95, "step": 5}},
    {"pointer": "/transport/poll_interval_ms", "range": {"from": 1, "to": 20, "step": 1}}
  ],
  "replications": $replications,
  "seed": 1
}
EOF

out="$work/sweep_$runs"
rm -rf "$out"
echo "machine: $(nproc) cores, load before $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/time -f "%e %U %S" -o "$work/time_sweep" \
  "$latsim" sweep "$work/scale.json" --out "$out" -j 2 --keep "$keep" > "$work/sweep.log"
/usr/bin/time -f "%e %U %S" -o "$work/time_report" "$latsim" report "$out" > "$work/report.log" 2>&1
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
read -r sw su ss < "$work/time_sweep"
read -r rw ru rs < "$work/time_report"
bytes=$(du -sb "$out" | cut -f1)
files=$(find "$out" -type f | wc -l)
printf '%d-run sweep (-j2, --keep %s): %.1f s wall, %.1f s CPU\n' "$runs" "$keep" "$sw" "$(echo "$su + $ss" | bc -l)"
printf 'report: %.1f s wall, %.1f s CPU (%s)\n' "$rw" "$(echo "$ru + $rs" | bc -l)" "$(tail -1 "$work/report.log")"
printf 'directory: %s (du -sh), %d bytes apparent, %d files, %.1f KB per run\n' \
  "$(du -sh "$out" | cut -f1)" "$bytes" "$files" "$(echo "$bytes / $runs / 1024" | bc -l)"
for f in results.csv results.sqlite; do printf '  %s: %s\n' "$f" "$(du -h "$out/$f" | cut -f1)"; done
one="$(find "$out/runs" -mindepth 1 -maxdepth 1 -type d -print -quit)"
printf '  one run: %s\n' "$(ls -l "$one" | awk 'NR > 1 {printf "%s %s B; ", $9, $5}')"
status=0
if [ "$runs" -eq 2000 ]; then
  kb=$(du -sk "$out" | cut -f1)
  if [ "$(echo "$rw >= 60" | bc -l)" = 1 ]; then echo "FAIL: the report took a minute or more"; status=1; fi
  if [ "$kb" -ge $((150 * 1024)) ]; then echo "FAIL: the directory takes 150 MB or more"; status=1; fi
fi
echo "work directory: $work"
exit $status
