#!/usr/bin/env bash
# Every class of bad input: exit code 2, one line on stderr naming the file
# and the JSON pointer, and no output files.
set -u
LATSIM=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
base='"duration_s": 1, "motion": {"type": "still"}, "tracker": {"rate_hz": 60}, "display": {"refresh_hz": 60}, "pipeline": {"type": "double_buffer", "render": {"fixed_ms": 1}}'

# check NAME EXPECTED_TEXT JSON_TEXT [extra args...]
check() {
  local name=$1 expect=$2 text=$3
  shift 3
  local file="$tmp/$name.json" out="$tmp/out_$name"
  printf '%s\n' "$text" >"$file"
  "$LATSIM" run "$file" --out "$out" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$?
  local lines
  lines=$(wc -l <"$tmp/stderr")
  if [ "$rc" -ne 2 ]; then echo "FAIL $name: exit code $rc, want 2"; fail=1; fi
  if [ "$lines" -ne 1 ]; then echo "FAIL $name: $lines lines on stderr, want 1"; cat "$tmp/stderr"; fail=1; fi
  if ! grep -qF "$file" "$tmp/stderr"; then echo "FAIL $name: stderr does not name the file"; fail=1; fi
  if ! grep -qF -- "$expect" "$tmp/stderr"; then echo "FAIL $name: stderr lacks '$expect':"; cat "$tmp/stderr"; fail=1; fi
  if [ -e "$out" ]; then echo "FAIL $name: output written"; fail=1; fi
  [ "$fail" -eq 0 ] && echo "ok   $name: $(cat "$tmp/stderr")"
}

check malformed_json "line 2" "{
  \"duration_s\": ,
}"
check wrong_type "/display/width_px" "{$base, \"host\": {\"stereo\": true}, \"scene\": {}, \"output\": {}, \"transport\": {\"type\": \"direct\"}}" --set /display/width_px='"wide"'
check unknown_key "/tracker/rat_hz" "{\"duration_s\": 1, \"motion\": {\"type\": \"still\"}, \"tracker\": {\"rate_hz\": 60, \"rat_hz\": 5}, \"display\": {}, \"pipeline\": {\"type\": \"double_buffer\", \"render\": {}}}"
check unknown_top_key "/pipelin" "{$base, \"pipelin\": {}}"
check negative_rate "/tracker/rate_hz" "{$base}" --set /tracker/rate_hz=-60
check zero_period "/display/refresh_hz" "{$base}" --set /display/refresh_hz=0
check negative_duration "/duration_s" "{$base}" --set /duration_s=-5
check out_of_range "/display/hfov_deg" "{$base}" --set /display/hfov_deg=400
check bad_choice "/display/scanout" "{$base}" --set /display/scanout='"frame"'
check unknown_pipeline "/pipeline/type" "{$base}" --set /pipeline/type='"quadruple_buffer"'
check missing_section "/display" "{\"motion\": {\"type\": \"still\"}, \"tracker\": {}, \"pipeline\": {\"type\": \"double_buffer\", \"render\": {}}}"
check bad_override "/nothing/here" "{$base}" --set /nothing/here=1
printf 't_s,px,py,pz,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n0.5,0,0,0,1,0,zero,0\n' >"$tmp/bad_trace.csv"
check malformed_trace "bad_trace.csv:3:" "{$base}" --set /motion='{"type": "trace", "file": "'"$tmp"'/bad_trace.csv"}'
check include_missing "/include" "{\"include\": \"no_such_base.json\", $base}"

"$LATSIM" run "$tmp/none.json" --out "$tmp/out_none" 2>"$tmp/stderr"
if [ $? -ne 2 ]; then echo "FAIL missing file: exit code"; fail=1; fi

exit $fail
