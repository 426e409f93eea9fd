#!/usr/bin/env bash
# Sweeps at scale: time, CPU and disk of a sweep of many 1 s runs and of its report.
#
#   bench/sweep_scale_bench.sh [LATSIM] [REPLICATIONS] [WORK_DIR] [KEEP]
#   environment: JOBS=2  JITTER_MS=0
#
# The shape of bench/sweep_shape.sh (the polled serial HMD cut to 1 simulated
# second, refresh 50..95 Hz x poll interval 1..20 ms) x REPLICATIONS (default
# 10: 2,000 runs; 100: 20,000; 500: 100,000). Runs `latsim sweep -j JOBS
# --keep KEEP` (default figures) into a fresh directory, then `latsim report`
# on it (its defaults), and prints for each the wall and CPU time, then the
# directory's size before the report (du), the files in it and the bytes per
# run, and what its parts take. Exit status 1 when a run takes more than
# 4 KB on disk by default (--keep figures).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
latsim="${1:-$root/build/latsim}"
replications="${2:-10}"
work="${3:-$(mktemp -d /tmp/latsim_scale_bench.XXXXXX)}"
keep="${4:-figures}"
jobs="${JOBS:-2}"
mkdir -p "$work"
runs=$((200 * replications))

# shellcheck source=bench/sweep_shape.sh
. "$here/sweep_shape.sh"
write_sweep_shape "$work/scale.json" "$replications" "${JITTER_MS:-0}"

out="$work/sweep_$runs"
rm -rf "$out"
echo "machine: $(nproc) cores, load before $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/time -f "%e %U %S %M" -o "$work/time_sweep" \
  "$latsim" sweep "$work/scale.json" --out "$out" -j "$jobs" --keep "$keep" --timings > "$work/sweep.log"
bytes=$(du -sb "$out" | cut -f1)
blocks=$(du -sk "$out" | cut -f1)
files=$(find "$out" -type f | wc -l)
/usr/bin/time -f "%e %U %S %M" -o "$work/time_report" "$latsim" report "$out" > "$work/report.log" 2>&1
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
read -r sw su ss sm < "$work/time_sweep"
read -r rw ru rs rm_ < "$work/time_report"
printf '%d-run sweep (-j%s, --keep %s): %.1f s wall, %.1f s CPU, peak %.0f MB\n' "$runs" "$jobs" "$keep" "$sw" \
  "$(echo "$su + $ss" | bc -l)" "$(echo "$sm / 1024" | bc -l)"
grep "timings\|per run" "$work/sweep.log" | sed 's/^/  /'
printf 'report: %.1f s wall, %.1f s CPU, peak %.0f MB (%s)\n' "$rw" "$(echo "$ru + $rs" | bc -l)" \
  "$(echo "$rm_ / 1024" | bc -l)" "$(tail -1 "$work/report.log")"
printf 'sweep and report: %.1f s wall\n' "$(echo "$sw + $rw" | bc -l)"
printf 'directory before the report: %d bytes apparent (%.2f KB a run), %d KB in blocks (%.2f KB a run), %d files\n' \
  "$bytes" "$(echo "$bytes / $runs / 1024" | bc -l)" "$blocks" "$(echo "$blocks / $runs" | bc -l)" "$files"
for f in store results.sqlite results.csv plan.json journal done runs; do
  printf '  %-15s %10d bytes, %.2f KB a run\n' "$f" "$(du -sb "$out/$f" | cut -f1)" \
    "$(echo "$(du -sb "$out/$f" | cut -f1) / $runs / 1024" | bc -l)"
done
status=0
if [ "$keep" = figures ] && [ "$bytes" -gt $((4096 * runs)) ]; then
  echo "FAIL: more than 4 KB a run on disk"
  status=1
fi
echo "work directory: $work"
exit $status
