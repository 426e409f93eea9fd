#!/usr/bin/env bash
# Same scenario and seed: byte-identical figures.json, timeline and ledger; a
# different seed changes a jittered run.
set -eu
LATSIM=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
args=(--set /duration_s=3 --set /tracker/jitter_ms=1 --ledger --samples -q)
"$LATSIM" run scenarios/hmd_60hz_serial_poll.json --out "$tmp/a" "${args[@]}"
"$LATSIM" run scenarios/hmd_60hz_serial_poll.json --out "$tmp/b" "${args[@]}"
for f in figures.json frames.csv samples.csv timeline.csv; do
  cmp "$tmp/a/$f" "$tmp/b/$f" || { echo "FAIL: $f differs between identical runs"; exit 1; }
done
"$LATSIM" run scenarios/hmd_60hz_serial_poll.json --out "$tmp/c" "${args[@]}" --seed 99
if cmp -s "$tmp/a/figures.json" "$tmp/c/figures.json"; then echo "FAIL: seed has no effect"; exit 1; fi
# The same for staged frames whose GPU time varies per frame, with a time-warp
# compositor preempting that GPU: same seed, same bytes; another seed, other times.
fs=(--set /duration_s=2 --set '/pipeline/stages/3/cost={"fixed_ms": 16.667, "variation": "uniform", "variation_fraction": 0.3}' --ledger --samples -q)
"$LATSIM" run scenarios/modern/timewarp_overload.json --out "$tmp/fa" "${fs[@]}"
"$LATSIM" run scenarios/modern/timewarp_overload.json --out "$tmp/fb" "${fs[@]}"
for f in figures.json frames.csv samples.csv timeline.csv; do
  cmp "$tmp/fa/$f" "$tmp/fb/$f" || { echo "FAIL: frame_stages $f differs between identical runs"; exit 1; }
done
"$LATSIM" run scenarios/modern/timewarp_overload.json --out "$tmp/fc" "${fs[@]}" --seed 99
if cmp -s "$tmp/fa/timeline.csv" "$tmp/fc/timeline.csv"; then echo "FAIL: frame_stages: seed has no effect"; exit 1; fi
# No temporary files are left behind by atomic writes.
if ls "$tmp"/a/*.tmp* >/dev/null 2>&1; then echo "FAIL: temporary files left"; exit 1; fi
# The ledger's stage durations add up exactly to scanout end minus measurement.
awk -F, 'NR > 1 {
  total = ($5 - $6) + ($6 - $7) + ($7 - $8) + ($8 - $9) + ($9 - $10) + ($10 - $11)
  if (-total != $11 - $5) { print "FAIL: ledger row " NR " does not add up"; exit 1 } }' "$tmp/a/frames.csv"
echo ok
