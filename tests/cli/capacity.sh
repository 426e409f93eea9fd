#!/usr/bin/env bash
# latsim capacity bisects for the largest triangle count without a missed
# field: Slats with the COPY optimisation sustains 140 and misses before 150.
set -eu
LATSIM=$1
out=$("$LATSIM" capacity scenarios/pxpl5/slats_140.json --max 400 --set /duration_s=2)
echo "$out"
n=${out#*=}
[ "$n" -ge 140 ] && [ "$n" -lt 150 ]
