#!/usr/bin/env bash
# Every complete scenario file shipped in scenarios/ validates.
set -eu
LATSIM=$1
mapfile -t files < <(find scenarios -name '*.json' | grep -v '/sweeps/' | grep -v '/base.json$' | sort)
"$LATSIM" validate "${files[@]}"
"$LATSIM" --help >/dev/null
"$LATSIM" run --help >/dev/null
