#!/usr/bin/env bash
# Every complete scenario file shipped in scenarios/ validates.
set -eu
LATSIM=$1
# Sweep files (a base and axes) are not scenarios, wherever they live.
mapfile -t files < <(find scenarios -name '*.json' | grep -v '/sweeps/' | grep -v '/base.json$' | sort | xargs grep -L '"axes":')
"$LATSIM" validate "${files[@]}"
"$LATSIM" --help >/dev/null
"$LATSIM" run --help >/dev/null
