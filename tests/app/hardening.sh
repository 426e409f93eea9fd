#!/usr/bin/env bash
# Regression tests for the defects a fuzzing campaign found (issue text:
# "Hardening"): every input below once crashed, hung, ran out of memory or
# answered with a library's raw text. Now `validate` and `run` both answer
# with exit code 2 and one readable line naming the file and the JSON
# pointer, and `run` leaves nothing behind.
set -u
LATSIM=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
# Costs no simulated time worth speaking of; every case changes one thing.
base='"duration_s": 1, "motion": {"type": "still"}, "tracker": {"rate_hz": 60}, "display": {"refresh_hz": 60}, "pipeline": {"type": "double_buffer", "render": {"fixed_ms": 1}}'
# An error line longer than this is not readable (one defect printed 4 MB).
max_line=600

say_fail() { echo "FAIL $*"; fail=1; }

# expect_bad NAME EXPECTED_TEXT FILE [extra args...]: validate and run alike.
expect_bad() {
  local name=$1 expect=$2 file=$3
  shift 3
  local out="$tmp/out_$name" cmd rc lines width
  for cmd in validate run; do
    if [ "$cmd" = run ]; then
      "$LATSIM" run "$file" --out "$out" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
    else
      "$LATSIM" validate "$file" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
    fi
    rc=$?
    lines=$(wc -l <"$tmp/stderr")
    width=$(awk '{ if (length($0) > w) w = length($0) } END { print w + 0 }' "$tmp/stderr")
    [ "$rc" -eq 2 ] || say_fail "$name ($cmd): exit code $rc, want 2"
    [ "$lines" -eq 1 ] || { say_fail "$name ($cmd): $lines lines on stderr, want 1"; head -c 2000 "$tmp/stderr"; }
    [ "$width" -le "$max_line" ] || say_fail "$name ($cmd): an error line of $width characters"
    grep -qF -- "$expect" "$tmp/stderr" || { say_fail "$name ($cmd): stderr lacks '$expect':"; head -c 600 "$tmp/stderr"; }
  done
  [ -e "$out" ] && say_fail "$name: run left $out"
  ls "$tmp" | grep -q "^out_$name\.tmp" && say_fail "$name: run left a staging directory"
  [ "$fail" -eq 0 ] && echo "ok   $name: $(head -c 300 "$tmp/stderr")"
}

# scenario NAME JSON: writes a scenario file and prints its path.
scenario() { printf '%s\n' "$2" >"$tmp/$1.json"; echo "$tmp/$1.json"; }

# 1. Deep nesting (was SIGSEGV): objects 100,000 deep, arrays 1,000,000 deep.
python3 -c 'import sys; sys.stdout.write("{\"x\":" + "{\"a\":" * 100000 + "1" + "}" * 100001)' >"$tmp/deep_object.json"
expect_bad deep_object "nested more than" "$tmp/deep_object.json"
python3 -c 'import sys; sys.stdout.write("{\"x\":" + "[" * 1000000 + "]" * 1000000 + "}")' >"$tmp/deep_array.json"
expect_bad deep_array "nested more than" "$tmp/deep_array.json"

# 2. An extreme pose (was SIGABRT inside Embree, and an empty directory left).
expect_bad far_position "/motion/position_m/0" \
  "$(scenario far_position '{"include": "'"$PWD"'/scenarios/frameless/side_by_side.json", "duration_s": 0.2,
     "motion": {"type": "still", "position_m": [1e20, 0, 0]}}')"

# 3. Rates finer than the time unit (never finished, or gigabytes of memory).
expect_bad rate_int64 "/pipeline/max_update_rate_hz" \
  "$(scenario rate_int64 '{"include": "'"$PWD"'/scenarios/arp/priority.json", "duration_s": 1,
     "pipeline": {"max_update_rate_hz": "9223372036854775807/1"}}')"
expect_bad tracker_rate "/tracker/rate_hz" "$(scenario tracker_rate "{$base}")" --set '/tracker/rate_hz="2000000000000/1"'
expect_bad refresh_1e6 "/display/refresh_hz" "$(scenario refresh "{$base}")" --set /display/refresh_hz=1e6
# A rate error whose exact period no 64-bit fraction holds (a period of
# 9223372036854775807/9223372036854775806 s times 1e9 / (1e9 + 1000)).
expect_bad rate_error_exact "/tracker/rate_error_ppm" "$(scenario rate_error "{$base}")" \
  --set '/tracker/rate_hz="9223372036854775806/9223372036854775807"' --set /tracker/rate_error_ppm=1

# 5. Errors while building models: a pointer and exit 2, not exit 1.
expect_bad huge_axis "/motion" "$(scenario huge_axis "{$base}")" \
  --set '/motion={"type": "constant", "rate_deg_s": 30, "axis": [1e308, 1e308, 1e308]}'
expect_bad walk_far "/motion/points/1/0" "$(scenario walk_far "{$base}")" \
  --set '/motion={"type": "walk", "points": [[0, 1.6, 0], [1e308, 1.6, -1e308]], "speed_m_s": 1}'
expect_bad serial_baud "/transport/baud" "$(scenario serial_baud "{$base}")" \
  --set '/transport={"type": "serial", "baud": 1e-9}'
long_name=$(printf 'n%.0s' $(seq 300))
expect_bad include_long_name "/include" "$(scenario include_long "{\"include\": \"$long_name.json\", $base}")"
expect_bad number_overflow "number out of range" "$(scenario overflow "{$base, \"seed\": 1e999}")"
grep -q "line 1" "$tmp/stderr" || say_fail "number_overflow: no line number"

# 6. A run-sizing product overflowing int64 picoseconds (validated, then failed at run time).
expect_bad binitize "/pipeline/binitize_us_per_bin" \
  "$(scenario binitize '{"include": "'"$PWD"'/scenarios/pxpl5/rc_min_latency.json", "duration_s": 0.5,
     "pipeline": {"binitize_us_per_bin": 1e12}}')"

# The same with Pixel-Planes 5's view workload, whose triangles are the
# geometry's, counted when the run builds it (once a run error, exit 1, or a
# frame that never finished): the room has hundreds of triangles, so 1e6 s
# per triangle or 1000 s per command in each of 20 regions cannot fit 1e6 s.
expect_bad view_rc_transform "/pipeline/transform_us_per_triangle" \
  "$(scenario view_rc_transform '{"include": "'"$PWD"'/scenarios/pxpl5/rc_room_walk.json", "duration_s": 0.5,
     "pipeline": {"transform_us_per_triangle": 1e12}}')"
expect_bad view_rc_render "/pipeline/render_us_per_command" \
  "$(scenario view_rc_render '{"include": "'"$PWD"'/scenarios/pxpl5/rc_room_walk.json", "duration_s": 0.5,
     "pipeline": {"render_us_per_command": 1e9}}')"
expect_bad view_slats_gp "/pipeline/gp_us_per_triangle" \
  "$(scenario view_slats_gp '{"include": "'"$PWD"'/scenarios/pxpl5/slats_room_walk.json", "duration_s": 0.5,
     "scene": {"file": "'"$PWD"'/scenarios/objects/room_lowpoly.obj"}, "pipeline": {"gp_us_per_triangle": 1e12}}')"

# Address recalculation: a render cost times the scene's items beyond what a
# run may last, a floor cut into billions of regions, a warp falloff that
# would have every vertex look at millions of regions.
expect_bad arp_per_object "/pipeline/render_per_object_us" \
  "$(scenario arp_per_object '{"include": "'"$PWD"'/scenarios/arp/priority.json", "duration_s": 0.5,
     "pipeline": {"render_per_object_us": 1e12}}')"
expect_bad arp_per_segment "/pipeline/render_per_segment_us" \
  "$(scenario arp_per_segment '{"include": "'"$PWD"'/scenarios/arp/gallery.json", "duration_s": 0.5,
     "pipeline": {"render_per_segment_us": 1e12}}')"
expect_bad arp_regions "/pipeline/region_size_m" \
  "$(scenario arp_regions '{"include": "'"$PWD"'/scenarios/arp/gallery.json", "duration_s": 0.5,
     "pipeline": {"region_size_m": 1e-6, "warp_falloff_m": 1e-6, "swap_margin_m": 1e-7}}')"
expect_bad arp_falloff "/pipeline/warp_falloff_m" \
  "$(scenario arp_falloff '{"include": "'"$PWD"'/scenarios/arp/gallery.json", "duration_s": 0.5,
     "pipeline": {"warp_falloff_m": 1e9}}')"

# 7. Includes that are not regular files; a directory given as the scenario.
expect_bad include_dev_zero "/include" "$(scenario dev_zero "{\"include\": \"/dev/zero\", $base}")"
expect_bad include_dot "/include" "$(scenario dot "{\"include\": \".\", $base}")"
expect_bad scenario_dir "directory" "$tmp"

# 9. Duplicate keys (last one used to win silently).
expect_bad duplicate_key "/display/refresh_hz" "$(scenario dup '{"duration_s": 1, "motion": {"type": "still"},
  "tracker": {"rate_hz": 60}, "display": {"refresh_hz": 60, "refresh_hz": 75},
  "pipeline": {"type": "double_buffer", "render": {"fixed_ms": 1}}}')"
grep -q "twice" "$tmp/stderr" || say_fail "duplicate_key: does not say the key is given twice"

# Messages of a readable length: a key of a megabyte.
python3 -c 'import sys; sys.stdout.write("{" + sys.argv[1] + ", \"" + "k" * 1000000 + "\": 1}")' "$base" >"$tmp/long_key.json"
expect_bad long_key "bytes" "$tmp/long_key.json"

# 10. Captures as costs (issue 29): read with the scenario, so validate and
# run both stop at the key, on one line of at most 300 characters.
capture_run() { # NAME TRACE_JSON: a double buffer whose render cost is TRACE_JSON
  scenario "$1" '{"duration_s": 1, "motion": {"type": "still"}, "tracker": {"rate_hz": 60},
    "display": {"refresh_hz": 60}, "pipeline": {"type": "double_buffer", "render": {"trace": '"$2"'}}}'
}
printf 'Application,ProcessID,MsGPUBusy\na.exe,1,2.5\nb.exe,2,3.5\na.exe,1,2.x5\n' >"$tmp/capture.csv"
mkfifo "$tmp/capture.fifo"
max_line=300 expect_bad capture_fifo "/pipeline/render/trace/file" \
  "$(capture_run capture_fifo '{"file": "capture.fifo", "column": "MsGPUBusy"}')"
grep -q "not a regular file" "$tmp/stderr" || say_fail "capture_fifo: does not say it is no regular file"
max_line=300 expect_bad capture_missing_column "/pipeline/render/trace/file" \
  "$(capture_run capture_column '{"file": "capture.csv", "column": "GPUBusy", "process_id": 1}')"
grep -q 'no column "GPUBusy".*its columns: Application, ProcessID, MsGPUBusy' "$tmp/stderr" ||
  say_fail "capture_missing_column: does not name the columns there are"
max_line=300 expect_bad capture_malformed_cell "/pipeline/render/trace/file" \
  "$(capture_run capture_cell '{"file": "capture.csv", "column": "MsGPUBusy", "application": "a.exe"}')"
grep -q "capture.csv:4: column 3 (MsGPUBusy) holds '2.x5'" "$tmp/stderr" ||
  say_fail "capture_malformed_cell: does not name line, column and value"
max_line=300 expect_bad capture_several_processes "/pipeline/render/trace/file" \
  "$(capture_run capture_several '{"file": "capture.csv", "column": "MsGPUBusy"}')"
grep -q "2 processes match the capture: choose one with application and process_id: a.exe 1, b.exe 2" "$tmp/stderr" ||
  say_fail "capture_several_processes: does not name the processes"
max_line=300 expect_bad capture_negative "/pipeline/render/trace/offset_ms" \
  "$(capture_run capture_negative '{"file": "capture.csv", "column": "MsGPUBusy", "process_id": 2, "offset_ms": -4}')"
max_line=300 expect_bad capture_with_terms "/pipeline/render/fixed_ms" \
  "$(scenario capture_terms '{"duration_s": 1, "motion": {"type": "still"}, "tracker": {"rate_hz": 60},
    "display": {"refresh_hz": 60}, "pipeline": {"type": "double_buffer",
    "render": {"fixed_ms": 1, "trace": {"file": "capture.csv", "column": "MsGPUBusy", "process_id": 2}}}}')"

# expect_ok NAME COMMAND...: exit 0 within a CPU-time bound (not wall time:
# the machine may be loaded), its stderr kept in $tmp/stderr.
expect_ok() {
  local name=$1
  shift
  (ulimit -t 60; "$@") >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$?
  [ "$rc" -eq 0 ] || { say_fail "$name: exit code $rc, want 0"; head -c 600 "$tmp/stderr"; }
}

# 4. The analytic calculation costs what the run costs, not what the render
# time or the repeat cycle would (a 1e8 ms render took over a minute of CPU).
# One frame of a 1e8 ms render spans 6e6 fields at 60 Hz, more than a 2 s run
# affords (4e6 fields at least), whether the phases are drawn (integrated)
# or fixed (enumerated): the figures say the calculation stopped short.
expect_ok analytic_long_render "$LATSIM" run scenarios/hmd_60hz_direct.json --out "$tmp/analytic1" -q \
  --set /duration_s=2 --set /pipeline/render/fixed_ms=1e8
grep -q '"complete": false' "$tmp/analytic1/figures.json" || say_fail "analytic_long_render: not marked incomplete"
expect_ok analytic_long_render_fixed "$LATSIM" run scenarios/hmd_60hz_direct.json --out "$tmp/analytic3" -q \
  --set /duration_s=2 --set /pipeline/render/fixed_ms=1e8 --set /display/phase_ms=0 --set /tracker/phase_ms=0
grep -q '"complete": false' "$tmp/analytic3/figures.json" || say_fail "analytic_long_render_fixed: not marked incomplete"
expect_ok analytic_slow_tracker "$LATSIM" run scenarios/hmd_60hz_direct.json --out "$tmp/analytic2" -q \
  --set /duration_s=2 --set '/tracker/rate_hz="1/1000000"'

# 9. Legal nonsense is a warning on stderr and in summary.json.
expect_ok slow_refresh "$LATSIM" run scenarios/hmd_60hz_direct.json --out "$tmp/slow_refresh" -q \
  --set /duration_s=2 --set /display/refresh_hz=0.001
grep -q "warning: no motion-to-photon latency figure" "$tmp/stderr" || say_fail "slow_refresh: no warning on stderr"
grep -q "no motion-to-photon latency figure" "$tmp/slow_refresh/summary.json" || say_fail "slow_refresh: no warning in summary.json"
# 2 s at 60 Hz: 120 samples are due; those not measured are the ones lost.
expect_ok jitter "$LATSIM" run scenarios/hmd_60hz_direct.json --out "$tmp/jitter" -q \
  --set /duration_s=2 --set /tracker/jitter_ms=1000
measured=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["figures"]["tracker_samples"])' "$tmp/jitter/summary.json")
grep -q "dropped $((120 - measured)) of 120 samples" "$tmp/stderr" || { say_fail "jitter: no warning of $((120 - measured)) of 120 lost"; cat "$tmp/stderr"; }
grep -q "dropped $((120 - measured)) of 120 samples" "$tmp/jitter/summary.json" || say_fail "jitter: no warning in summary.json"
[ "$measured" -lt 120 ] || say_fail "jitter: no sample was lost ($measured measured), the case tests nothing"

# 12. validate takes sweep files; --set makes a missing optional section; a
# pipeline change names the keys the new pipeline ignores, not whole sections.
expect_ok validate_sweep "$LATSIM" validate scenarios/sweeps/tracker_rate.json
grep -q "ok (sweep of 18 runs, 6 points)" "$tmp/stdout" || say_fail "validate_sweep: $(cat "$tmp/stdout")"
expect_ok set_creates_section "$LATSIM" run "$(scenario no_output "{$base}")" --set /output/timeline=false \
  --out "$tmp/no_output" -q
grep -q '"timeline": false' "$tmp/no_output/summary.json" || say_fail "set_creates_section: /output/timeline not applied"
expect_ok mode_keys "$LATSIM" validate scenarios/hmd_60hz_direct.json --set /pipeline/type=frameless
grep -q "warning: /pipeline/render: ignored: read only when type=double_buffer" "$tmp/stderr" ||
  say_fail "mode_keys: $(cat "$tmp/stderr")"
grep -q "warning: /scene:" "$tmp/stderr" && say_fail "mode_keys: the whole /scene section is flagged"

[ "$fail" -eq 0 ] && echo "ok   analytic, warnings, validate of sweeps, --set sections, per-mode keys"

# 13. Files a scenario points at. Only a regular file of bounded size is
# read (a trace that was a FIFO or /dev/zero hung until SIGKILL), and a mesh
# is read and checked with the scenario (a NaN vertex or a face of two
# vertices was found at t = 0.07 s, exit 1, and validate accepted it): exit 2,
# one line naming the pointer that named the file, and the file's line.
no_motion='"duration_s": 1, "tracker": {"rate_hz": 60}, "display": {"refresh_hz": 60}, "pipeline": {"type": "double_buffer", "render": {"fixed_ms": 1}}'
mkfifo "$tmp/trace_fifo.txt"
expect_bad trace_fifo "/motion/file: $tmp/trace_fifo.txt: cannot read the trace file: it is not a regular file" \
  "$(scenario trace_fifo "{$no_motion, \"motion\": {\"type\": \"trace\", \"file\": \"$tmp/trace_fifo.txt\"}}")"
expect_bad trace_dev_zero "/motion/file: /dev/zero: cannot read the trace file: it is not a regular file" \
  "$(scenario trace_dev_zero "{$no_motion, \"motion\": {\"type\": \"trace\", \"file\": \"/dev/zero\"}}")"
printf 'v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$tmp/nan.obj"
expect_bad mesh_nan "/scene/file: $tmp/nan.obj:1: non-numeric value 'nan'" \
  "$(scenario mesh_nan "{$base, \"scene\": {\"type\": \"obj\", \"file\": \"$tmp/nan.obj\"}}")"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n' >"$tmp/two_vertices.obj"
expect_bad mesh_two_vertex_face "/scene/file: $tmp/two_vertices.obj:5: too few vertices in face: 2" \
  "$(scenario mesh_two_vertex_face "{$base, \"scene\": {\"type\": \"obj\", \"file\": \"$tmp/two_vertices.obj\"}}")"
mkfifo "$tmp/mesh_fifo.obj"
expect_bad mesh_fifo "/scene/file: $tmp/mesh_fifo.obj: cannot read the mesh: it is not a regular file" \
  "$(scenario mesh_fifo "{$base, \"scene\": {\"type\": \"obj\", \"file\": \"$tmp/mesh_fifo.obj\"}}")"
# An include error names the chain: the included file at fault, and the
# file and pointer that included it (once it named only /etc/passwd).
expect_bad include_chain "(included by $tmp/include_passwd.json at /include)" \
  "$(scenario include_passwd '{"include": "/etc/passwd"}')"
# Usage errors are one line too (the option parser printed two).
for args in "run" "run --bogus x.json" "validate" "sweep" "fidelity x.json --vary /a=1" "report"; do
  # shellcheck disable=SC2086
  "$LATSIM" $args >"$tmp/stdout" 2>"$tmp/stderr"
  rc=$?
  [ "$rc" -eq 2 ] || say_fail "usage '$args': exit code $rc, want 2"
  [ "$(wc -l <"$tmp/stderr")" -eq 1 ] || { say_fail "usage '$args': $(wc -l <"$tmp/stderr") lines on stderr"; cat "$tmp/stderr"; }
done
# A time no single key holds names the object it comes from, and prints its
# number shortly (was "cannot build the scenario: simulation time out of
# range: 1000000000000.000000 ms", naming no key).
expect_bad time_overflow_render "/pipeline/render: simulation time out of range: 1000000000000 ms" \
  "$(scenario time_overflow_render '{"duration_s": 1, "motion": {"type": "still"}, "tracker": {"rate_hz": 60},
     "display": {"refresh_hz": 60}, "pipeline": {"type": "double_buffer", "render": {"fixed_ms": 1e12}}}')"
# 1e9 ms + 1e7 triangles x 1e6 us: 1.1e10 ms, past the int64 picosecond range.
expect_bad time_overflow_sum "/pipeline/render: simulation time out of range: 11000000000 ms" \
  "$(scenario time_overflow_sum '{"duration_s": 1, "motion": {"type": "still"}, "tracker": {"rate_hz": 60},
     "display": {"refresh_hz": 60}, "scene": {"triangles": 10000000},
     "pipeline": {"type": "double_buffer", "render": {"fixed_ms": 1e9, "per_primitive_us": 1e6}}}')"
# A trace past its size limit is refused before it is read.
truncate -s 300M "$tmp/huge_trace.txt"
expect_bad trace_too_large "cannot read the trace file: it is too large (314572800 bytes; at most 268435456)" \
  "$(scenario trace_too_large "{$no_motion, \"motion\": {\"type\": \"trace\", \"file\": \"$tmp/huge_trace.txt\"}}")"
# 14. Runs that could never finish (a 1 ps render without vsync, a 1 ps
# motion-phase step: unbounded events, ended only by a kill) are refused
# before they start, at the key that drives the estimate. 1 ps frames back to
# back: 1e12 events per simulated second, 1e13 over 10 s; the grid of
# motion phases, one step per picosecond: 1e12 steps in 1 s.
expect_bad render_1ps "/pipeline/render: about 1.0e13 events over 10 s (limit 2e9; --max-events raises it)" \
  "$(scenario render_1ps '{"duration_s": 10, "motion": {"type": "still"}, "tracker": {"rate_hz": 60},
     "display": {"refresh_hz": 60}, "pipeline": {"type": "double_buffer", "vsync": false, "render": {"fixed_ms": 1e-9}}}')"
expect_bad phase_step_1ps "/motion_phases/step_ms: about 1.0e12 steps of work over 1 s" \
  "$(scenario phase_step_1ps "{$base, \"motion_phases\": {\"step_ms\": 1e-9}}")"
# The limit is a parameter: 1 s of the base scenario is about 180 events (60
# tracker samples, 60 retraces, 60 frames); 100 refuses it, 0 lifts the limit.
expect_bad max_events_low "about 1.8e2 events over 1 s (limit 1e2" "$(scenario max_events "{$base}")" --max-events 100
expect_ok max_events_off "$LATSIM" validate "$tmp/max_events.json" --max-events 0

# 15. A Pixel-Planes 5 ring rate so slow that a field's or a frame's words
# take longer than a run may last (their transfer times overflowed simulated
# time in the middle of the run): refused at the ring rate.
expect_bad ring_slats "/pipeline/ring_mwords_per_s" \
  "$(scenario ring_slats '{"include": "'"$PWD"'/scenarios/pxpl5/slats_140.json", "duration_s": 0.5,
     "pipeline": {"ring_mwords_per_s": 1e-12}}')"
expect_bad ring_rc "/pipeline/ring_mwords_per_s" \
  "$(scenario ring_rc '{"include": "'"$PWD"'/scenarios/pxpl5/rc_min_latency.json", "duration_s": 0.5,
     "pipeline": {"ring_mwords_per_s": 1e-12}}')"

# 16. A key the chosen mode does not read is still checked against its
# declaration (a still head given "points": "garbage" was only "ignored");
# a well-typed one stays a warning (mode_keys above).
expect_bad ignored_garbage "/motion/points: " "$(scenario ignored_garbage "{$base}")" \
  --set '/motion={"type": "still", "points": "garbage"}'
expect_bad ignored_range "/pipeline/chunk_pixels: " "$(scenario ignored_range "{$base}")" \
  --set /pipeline/chunk_pixels=-5
expect_bad ignored_nested "/pipeline/timewarp/strips: " "$(scenario ignored_nested "{$base}")" \
  --set '/pipeline/timewarp={"strips": "many", "stages": []}'
[ "$fail" -eq 0 ] && echo "ok   event budget, ring rate, ignored keys checked"

# 17. Options are checked before any work, by every command (issue 47): an
# output path that is a file or lies under one, a tolerance no double can
# reach (1e-300 ran without end; nan was exit 1 naming an internal
# function), a bound out of range (printed DBL_MAX in full). Exit 2, one
# line naming the option, within a CPU-time bound far below one run's cost,
# and nothing made.
# expect_usage NAME EXPECTED_TEXT COMMAND...
expect_usage() {
  local name=$1 expect=$2 rc width
  shift 2
  ( ulimit -t 20; "$@" ) >"$tmp/stdout" 2>"$tmp/stderr"
  rc=$?
  width=$(awk '{ if (length($0) > w) w = length($0) } END { print w + 0 }' "$tmp/stderr")
  [ "$rc" -eq 2 ] || say_fail "$name: exit code $rc, want 2"
  [ "$(wc -l <"$tmp/stderr")" -eq 1 ] || { say_fail "$name: $(wc -l <"$tmp/stderr") lines on stderr"; head -c 600 "$tmp/stderr"; }
  [ "$width" -le "${usage_width:-300}" ] || say_fail "$name: an error line of $width characters"
  grep -qF -- "$expect" "$tmp/stderr" || { say_fail "$name: stderr lacks '$expect':"; head -c 600 "$tmp/stderr"; }
  grep -q "1.79769\|e+308" "$tmp/stderr" && say_fail "$name: a bound printed as DBL_MAX"
}
S=scenarios/hmd_60hz_direct.json
vary=(--vary /pipeline/render/fixed_ms=1:10 --minimise motion_to_photon_ms.mean)
for cmd in "run $S" "optimise $S ${vary[*]}" "capacity $S" \
           "fidelity $S --vary /tracker/rate_hz=60,120 --metric motion_to_photon_ms.mean" \
           "sweep scenarios/sweeps/tracker_rate.json" "compare $S $tmp"; do
  # shellcheck disable=SC2086
  expect_usage "${cmd%% *} --out /dev/null" "--out \"/dev/null\" exists and is not a directory" "$LATSIM" $cmd --out /dev/null
  # shellcheck disable=SC2086
  expect_usage "${cmd%% *} --out under a file" "which is not a directory" "$LATSIM" $cmd --out /dev/null/x
done
expect_usage "compare --out empty" "--out must name a directory" "$LATSIM" compare "$S" "$tmp" --out ""
# 1e-9 of the interval's larger end (10 ms) is 1e-8: the golden section
# keeps 0.618 of the interval a step, so that bound ends after 44 steps.
expect_usage optimise_tolerance_tiny "--tolerance must be a finite number of at least 1e-08" \
  "$LATSIM" optimise "$S" "${vary[@]}" --tolerance 1e-300
expect_usage optimise_tolerance_nan 'got "nan"' "$LATSIM" optimise "$S" "${vary[@]}" --tolerance nan
expect_usage optimise_vary_inf "expected /json/pointer=LO:HI with finite LO < HI" \
  "$LATSIM" optimise "$S" --vary /pipeline/render/fixed_ms=0:inf --minimise motion_to_photon_ms.mean
expect_usage capacity_threshold_huge 'got "1e999"' "$LATSIM" capacity "$S" --threshold 1e999
expect_usage run_max_events_negative 'got "-1"' "$LATSIM" run "$S" --out "$tmp/max_events_neg" --max-events -1
[ -e "$tmp/max_events_neg" ] && say_fail "run --max-events -1 made its output directory"

# 18. Messages print numbers as given: an integer past int64 is not wrapped
# (2^63 was "-9223372036854775808"), a value just past a bound is not
# rounded onto it (1e12 + 1 was "1e+12"); a NUL in a file name is refused
# (it cut the name short: another file, read silently).
expect_bad integer_2_63 "got 9223372036854775808" "$S" --set /scene/triangles=9223372036854775808
expect_bad fixed_past_bound "got 1000000000001" "$S" --set /pipeline/render/fixed_ms=1000000000001
expect_bad nul_in_path "/pipeline/render/trace/file: contains a NUL character" \
  "$(scenario nul_in_path '{"include": "'"$PWD/$S"'", "pipeline": {"render": {"trace": {"file": "a\u0000b"}}}}')"
expect_bad frequency_tiny "/tracker/rate_hz: a frequency given as a number must be at least 1e-06 Hz" "$S" \
  --set /tracker/rate_hz=1e-9
# An interrupt-driven serial host whose handlers (1e12 us a character) back
# up past the 1e6 s a run may last: refused at the key, not a time overflow
# in the middle of the run.
expect_bad serial_interrupt_backlog "/transport/per_char_interrupt_us" scenarios/hmd_60hz_serial_interrupt.json \
  --set /transport/per_char_interrupt_us=1e12
# 1e9 us (1000 s) passes the per-record bound (32 characters: 32000 s), but
# the backlog carried over the run's 3600 records (60 s at 60 Hz) is 32 x
# 3600 = 115200 handlers: 1.152e8 s.
expect_bad serial_interrupt_run_backlog "1000 s × record_bytes × the run's records (duration_s × /tracker/rate_hz) (115200)" \
  scenarios/hmd_60hz_serial_interrupt.json --set /transport/per_char_interrupt_us=1e9
# 19. Post-processing has a cost the event budget counts like events:
# apparent latency's windows 1e-9 ms apart fit every window's samples at
# every shift, 1e12 windows per simulated second (it passed validate, then
# spun after the simulation without end); refused at the key that drives it.
expect_bad apparent_latency_step "/apparent_latency/step_ms: about" scenarios/measurement/min_jerk_rig.json \
  --set /apparent_latency/step_ms=1e-9
grep -q "steps of work" "$tmp/stderr" || say_fail "apparent_latency_step: not counted as steps of work"
[ "$fail" -eq 0 ] && echo "ok   options checked before work; numbers as given; NUL refused"

# 20. Found by the campaign (tests/app/campaign.py), round three.
# A positive duration shorter than the time unit rounds to 0 ps: refused at
# its key where 0 is out of range (a 1e-308 ms apparent-latency step passed
# validate and then never advanced; a flash, a motion-phase step or window of
# 1e-308 ms failed with no pointer).
for key in /apparent_latency/step_ms /display/persistence/lit_ms /motion_phases/step_ms /motion_phases/window_ms; do
  expect_bad "rounds_to_zero_${key//\//_}" "$key: rounds to 0 in the time unit, 1 ps (1e-09 ms), got 1e-308" \
    scenarios/measurement/min_jerk_rig.json --set "$key=1e-308"
done
# A frame-to-frame correlation is a property of a normal variation's draws:
# with a uniform variation it is refused at its key, not silently ignored.
expect_bad correlated_uniform "/pipeline/stages/0/cost/variation_correlation_frames: only a normal variation" \
  scenarios/pacing/base.json --set /pipeline/stages/0/cost/variation=uniform \
  --set /pipeline/stages/0/cost/variation_correlation_frames=90

# Number options are read whole, in range, as given: an unsigned -1 was
# 18446744073709551615, "" was 0, 2^64 was clamped, 1e-400 (a --max-events of
# 0) lifted the event budget.
expect_usage seed_negative '--seed: expected an integer from 0 to 18446744073709551615, got "-1"' \
  "$LATSIM" run "$S" --out "$tmp/seed_neg" --seed -1
expect_usage seed_empty '--seed: expected an integer from 0 to 18446744073709551615, got ""' \
  "$LATSIM" fidelity "$S" --out "$tmp/seed_empty" --seed "" --vary /tracker/rate_hz=60,120 --metric frames_missed
expect_usage replication_2_64 'got "18446744073709551616"' \
  "$LATSIM" run "$S" --out "$tmp/rep_big" --replication 18446744073709551616
expect_usage max_events_underflow '--max-events: expected a finite number within a double'"'"'s range, got "1e-400"' \
  "$LATSIM" validate "$S" --max-events 1e-400
# A long or hostile option value is cut and escaped, and the line with its
# hint stays within 400 characters (a 3,000-digit --jobs made a line of 454).
usage_width=400 expect_usage jobs_long "--jobs" "$LATSIM" sweep scenarios/sweeps/tracker_rate.json --out "$tmp/jobs_long" -j "$(printf '9%.0s' $(seq 3000))"
# --shard "" ran the whole sweep as if not given; an escape sequence was echoed raw.
expect_usage shard_empty '--shard: "": expected I/N' "$LATSIM" sweep scenarios/sweeps/tracker_rate.json --out "$tmp/shard_empty" --shard ""
[ -e "$tmp/shard_empty" ] && say_fail "shard_empty: the sweep ran"
expect_usage shard_escape '--shard: "\x1B[31m": expected I/N' "$LATSIM" sweep scenarios/sweeps/tracker_rate.json \
  --out "$tmp/shard_escape" --shard $'\e[31m'
# An --out name no file system holds was found only when the results were
# written, after the run (exit 1).
expect_usage out_name_too_long "has a name longer than a file name may be (255 bytes)" \
  "$LATSIM" run "$S" --out "$tmp/$(printf 'n%.0s' $(seq 300))"
# An unknown choice quotes the value cut (a 5,000-character one made a line of 5,098).
expect_bad unknown_value_long '/motion/type: unknown value "zzzz' "$S" \
  --set "/motion/type=\"$(printf 'z%.0s' $(seq 5000))\""
[ "$(awk '{ print length($0) }' "$tmp/stderr")" -le 400 ] || say_fail "unknown_value_long: a line over 400 characters"
# Captures: a NUL byte (read as text, or a message cut at it) and a column
# named twice (the first taken, silently) are refused by every reader.
run_dir="$tmp/capture_base_run"
"$LATSIM" run "$S" --out "$run_dir" -q --set /duration_s=1 2>/dev/null || say_fail "capture base run"
# (A column no reader asks for may repeat: each file repeats one that is read.)
for pair in "scenarios/measured/captures/ovr-metrics/OGMP_1.csv:Time Stamp" \
            "scenarios/measured/captures/vrapi/vrapi_stats_lines.txt:FPS" \
            "tests/models/capture/data/steamvr_frame_timing.csv:m_flSystemTimeInSeconds"; do
  capture=${pair%%:*} column=${pair#*:}
  name=$(basename "$capture")
  python3 -c 'import sys; d = open(sys.argv[1], "rb").read(); n = len(d) // 3; open(sys.argv[2], "wb").write(d[:n] + b"\0" + d[n:])' \
    "$capture" "$tmp/nul_$name"
  expect_usage "capture_nul_$name" "a NUL byte at column" "$LATSIM" compare "$tmp/nul_$name" "$run_dir" --out "$tmp/cmp_nul" --no-plots
  python3 -c 'import sys; h, _, rest = open(sys.argv[1], "rb").read().partition(b"\n")
sep = b"=72/72," if h.startswith(b"FPS=") else b","
open(sys.argv[2], "wb").write(h + b"," + sys.argv[3].encode() + sep + b"\n" + rest)' "$capture" "$tmp/twice_$name" "$column"
  expect_usage "capture_twice_$name" "column \"$column\" appears twice in the header" "$LATSIM" compare "$tmp/twice_$name" "$run_dir" --out "$tmp/cmp_twice" --no-plots
done
[ -e "$tmp/cmp_nul" ] || [ -e "$tmp/cmp_twice" ] && say_fail "a refused capture made compare's directory"
# report: a control character in a table latsim wrote is damage (a NUL or an
# escape sequence in results.csv was read as text, exit 0); its one line names the file once.
printf '{"base": "%s", "overrides": {"/duration_s": 0.5}, "axes": [{"pointer": "/tracker/rate_hz", "values": [60, 120]}]}' \
  "$PWD/$S" >"$tmp/ctrl_sweep.json"
"$LATSIM" sweep "$tmp/ctrl_sweep.json" --out "$tmp/ctrl_sweep" -j 2 >/dev/null 2>&1 || say_fail "control-character corpus sweep"
sed -i '2s/,/,\x1b[2J/' "$tmp/ctrl_sweep/results.csv"
expect_usage report_escape_in_table "results.csv: line 2: a control character (\x1B): not a table latsim writes" \
  "$LATSIM" report "$tmp/ctrl_sweep"
[ "$(grep -o 'results.csv' "$tmp/stderr" | wc -l)" -eq 1 ] || say_fail "report_escape_in_table: the file named more than once"
[ "$fail" -eq 0 ] && echo "ok   campaign round three: rounding to 0 ps, number options, --shard, --out names, captures, tables"
exit $fail
