#!/usr/bin/env bash
# The main job: set up, build, run the default scenario set (every pipeline
# side by side) into out/, and write the report (tables, plots, frames). A
# line of the set that names a sweep file (one with "axes") runs as a sweep
# into its own directory, with its own report; the main report shows its table
# and distributions too.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")"
# The main job needs the command only: tests and the Python module are built by ./test.sh.
TARGET=latsim scripts/setup.sh
OUT=${OUT:-out}
rm -rf "$OUT.partial"
mkdir -p "$OUT.partial"
while read -r scenario; do
  case "$scenario" in ''|'#'*) continue ;; esac
  name=$(basename "$scenario" .json)
  if grep -q '"axes"' "scenarios/$scenario"; then
    build/latsim sweep "scenarios/$scenario" --out "$OUT.partial/$name" --keep first
    build/latsim report "$OUT.partial/$name" >/dev/null
  else
    build/latsim run "scenarios/$scenario" --out "$OUT.partial/$name" --ledger
  fi
done < scenarios/default_set.txt
# Frameless beside double buffering at the same budget, with the truth: one strip per capture.
if [ -d "$OUT.partial/side_by_side" ] && [ -d "$OUT.partial/double_buffered" ]; then
  /usr/bin/python3 analysis/side_by_side.py "$OUT.partial/side_by_side" "$OUT.partial/double_buffered" \
    "$OUT.partial/frameless_vs_double_buffering" >/dev/null
fi
build/latsim report "$OUT.partial" --title "$(basename "$OUT")"
# Replace the previous results only once everything succeeded.
rm -rf "$OUT"
mv "$OUT.partial" "$OUT"
echo "results: $OUT/report.md"
