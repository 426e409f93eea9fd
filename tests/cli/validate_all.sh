#!/usr/bin/env bash
# Every complete scenario file shipped in scenarios/ validates.
set -eu
LATSIM=$1
mapfile -t files < <(grep -rl '"pipeline"' scenarios --include='*.json' | grep -v '/sweeps/' | sort)
"$LATSIM" validate "${files[@]}"
"$LATSIM" --help >/dev/null
"$LATSIM" run --help >/dev/null
