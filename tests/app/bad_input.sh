#!/usr/bin/env bash
# Every class of bad input: exit code 2, one line on stderr naming the file
# and the JSON pointer, and no output files.
set -u
LATSIM=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
shared='"duration_s": 1, "motion": {"type": "still"}, "tracker": {"rate_hz": 60}, "display": {"refresh_hz": 60}'
base="$shared"', "pipeline": {"type": "double_buffer", "render": {"fixed_ms": 1}}'

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

# Display clock noise: jitter that could make a field start before the previous
# one's last pixel (4 sigma above a quarter of the 6.68 us slack), and the
# Pixel-Planes 5 engines, which keep a steady clock of their own; USB HID rates.
check clock_jitter "/display/clock_noise/jitter_ns_rms" "{$base}" --set /display/clock_noise='{"jitter_ns_rms": 500}'
check clock_negative_wander "/display/clock_noise/wander_ppm_per_sqrt_s" "{$base}" --set /display/clock_noise='{"wander_ppm_per_sqrt_s": -1}'
check usb_poll_rate "/transport/poll_hz" "{$base}" --set /transport='{"type": "usb_hid", "poll_hz": 0}'
check usb_negative_delay "/transport/os_delay_ms" "{$base}" --set /transport='{"type": "usb_hid", "os_delay_ms": -1}'

# The staged frame pipeline's cross-field rules and the display's persistence.
# (A key given twice is refused, so the pipeline is given once.)
fs="$shared"', "pipeline": {"type": "frame_stages", "processors": [{"name": "cpu"}, {"name": "gpu"}], "stages": [{"name": "I", "on": "cpu", "samples_pose": true, "cost": {"fixed_ms": 1}}, {"name": "G", "on": "gpu", "cost": {"fixed_ms": 1}}]}'
warp='{"stages": [{"name": "W", "on": "gpu", "samples_pose": true, "cost": {"fixed_ms": 1}}]}'
check fs_unknown_processor "/pipeline/stages/1/on" "{$fs}" --set /pipeline/stages/1/on='"gpu2"'
check fs_duplicate_processor "/pipeline/processors/1/name" "{$fs}" --set /pipeline/processors/1/name='"cpu"'
check fs_stream_first "/pipeline/stages/0/start" "{$fs}" --set /pipeline/stages/0/start='"stream"'
check fs_stream_same_processor "/pipeline/stages/1/start" "{$fs}" --set /pipeline/stages/1/on='"cpu"' --set /pipeline/stages/1/start='"stream"'
check fs_until_earlier "/pipeline/stages/1/until" "{$fs}" --set /pipeline/stages/1/start='"late"' --set /pipeline/stages/1/until='"I"'
check fs_until_not_late "/pipeline/stages/0/until" "{$fs}" --set /pipeline/stages/0/until='"G"'
check fs_no_pose "/pipeline/stages:" "{$fs}" --set /pipeline/stages/0/samples_pose=false
check fs_no_stages "/pipeline/stages:" "{$fs}" --set /pipeline/stages='[]'
check fs_endless "/pipeline/vsync" "{$fs}" --set /pipeline/vsync=false --set /pipeline/stages/0/cost/fixed_ms=0 --set /pipeline/stages/1/cost/fixed_ms=0
check fs_warp_no_pose "/pipeline/timewarp/stages:" "{$fs}" --set /pipeline/timewarp='{"stages": [{"name": "W", "on": "gpu", "cost": {"fixed_ms": 1}}]}'
check fs_warp_no_stages "/pipeline/timewarp/stages:" "{$fs}" --set /pipeline/timewarp='{"stages": []}'
check fs_strips_field "/pipeline/timewarp/strips" "{$fs}" --set /pipeline/timewarp="$warp" --set /pipeline/timewarp/strips=4
check fs_strips_lines "/pipeline/timewarp/strips" "{$fs}" --set /display/scanout='"line"' --set /pipeline/timewarp="$warp" --set /pipeline/timewarp/strips=10000
check persistence_too_long "/display/persistence/lit_ms" "{$fs}" --set /display/persistence='{"type": "rolling", "lit_ms": 20}'
check persistence_no_lit "/display/persistence/lit_ms" "{$fs}" --set /display/persistence='{"type": "global"}'
check persistence_type "/display/persistence/type" "{$fs}" --set /display/persistence='{"type": "half"}'
check persistence_response "/display/persistence/response_ms" "{$fs}" --set /display/persistence='{"type": "full", "response_ms": -1}'

# A see-through headset's rig films the real object of /pipeline/object beside its image: never a controller.
pt="$shared"', "pipeline": {"type": "passthrough", "camera": {"height_px": 1000, "exposure_ms": 2, "row_readout_us": 2, "shutter": "global", "sync": "display"}, "isp": {"fixed_ms": 1.5}, "compositor": {"start": "before_retrace", "lead_ms": 2, "reprojection_ms": 1}, "object": {"type": "still"}, "rig": {"fps": 1000}}'
check passthrough_rig_controller "/pipeline/rig/object: a passthrough rig films the real object of /pipeline/object" "{$pt}" --set /pipeline/rig/object='"controller"'

"$LATSIM" run "$tmp/none.json" --out "$tmp/out_none" 2>"$tmp/stderr"
if [ $? -ne 2 ]; then echo "FAIL missing file: exit code"; fail=1; fi

exit $fail
