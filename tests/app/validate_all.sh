#!/usr/bin/env bash
# Every complete scenario file shipped in scenarios/ validates, and so does every point of every shipped sweep.
set -eu
LATSIM=$1
# Sweep files (a base and axes) are not scenarios, wherever they live.
mapfile -t files < <(find scenarios -name '*.json' | grep -v '/sweeps/' | grep -v '/base.json$' | sort | xargs grep -L '"axes":')
"$LATSIM" validate "${files[@]}"
# Every shipped sweep: each of its points is a valid scenario (--check runs and writes nothing).
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mapfile -t sweeps < <(find scenarios -name '*.json' | sort | xargs grep -l '"axes":')
for sweep in "${sweeps[@]}"; do
  "$LATSIM" sweep "$sweep" --out "$tmp/out" --check
done
[ ! -e "$tmp/out" ]
"$LATSIM" --help >/dev/null
"$LATSIM" run --help >/dev/null
