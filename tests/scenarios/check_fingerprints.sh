#!/usr/bin/env bash
# Runs every shipped scenario for two simulated seconds and compares the
# fingerprint of its event trace with the pinned value. A difference means
# behaviour changed: if that was intended, re-pin with --update and say why
# in the commit message.
set -eu
LATSIM=$1
UPDATE=${2:-}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
pinned="$here/fingerprints.txt"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Sweep files (a base and axes) are not scenarios, wherever they live.
mapfile -t files < <(find scenarios -name '*.json' | grep -v '/sweeps/' | grep -v '/base.json$' | sort | xargs grep -L '"axes":')
: >"$tmp/now.txt"
for f in "${files[@]}"; do
  out="$tmp/run"
  rm -rf "$out"
  "$LATSIM" run "$f" --out "$out" --set /duration_s=2 -q
  fp=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['fingerprint'])" "$out/figures.json")
  echo "$f $fp" >>"$tmp/now.txt"
done
if [ "$UPDATE" = "--update" ]; then
  cp "$tmp/now.txt" "$pinned"
  echo "pinned $(wc -l <"$pinned") fingerprints"
  exit 0
fi
if ! diff -u "$pinned" "$tmp/now.txt"; then
  echo "FAIL: scenario fingerprints changed (see diff above)"
  exit 1
fi
echo "ok: $(wc -l <"$pinned") scenario fingerprints match"
