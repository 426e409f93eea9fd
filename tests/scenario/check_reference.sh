#!/usr/bin/env bash
# docs/scenario-reference.md is generated from the parameter declarations:
# it must equal what `latsim schema --format markdown` prints now. After a
# change to a declaration, regenerate it with
#   build/latsim schema --format markdown > docs/scenario-reference.md
set -eu
LATSIM=$1
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
"$LATSIM" schema --format markdown >"$tmp"
if ! diff -u docs/scenario-reference.md "$tmp"; then
  echo "FAIL: docs/scenario-reference.md differs from latsim schema --format markdown (regenerate it)"
  exit 1
fi
echo "ok: docs/scenario-reference.md is up to date"
