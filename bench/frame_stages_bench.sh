#!/usr/bin/env bash
# Cost of today's pipelines, each against a peer in the same run.
#
#   bench/frame_stages_bench.sh [LATSIM] [REPEATS]
#
# 1. The reference vsync configuration as staged frames (frame_stages: four
#    stages on a CPU thread and a GPU) against the same system as one
#    double-buffered renderer (4 ms frames), 60 simulated seconds at line
#    scanout on the 480-line reference display; the two give the same latency
#    distribution (tests/pipelines/frame_stages), so the ratio is the price of the stages.
# 2. The time-warp overload scenario (90 Hz, 1200 lines at field scanout,
#    preemptible GPU, a compositor per refresh) against the same application
#    without the compositor (frames swapped in at retraces).
# 3. The low-persistence scenario with and without its persistence model
#    (mid-lit photon times and the smear figure per span).
# Runs alternate, REPEATS (default 5) times each; prints the median wall time
# of the simulation (summary.json wall_s), events and the ratio.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
latsim="${1:-$root/build/latsim}"
repeats="${2:-5}"
work="$(mktemp -d /tmp/latsim_frame_stages_bench.XXXXXX)"
trap 'rm -rf "$work"' EXIT
modern="$root/scenarios/modern"

run() {  # name scenario overrides...
  local name=$1 scenario=$2
  shift 2
  local sets=()
  for o in "$@"; do sets+=(--set "$o"); done
  rm -rf "$work/$name"
  "$latsim" run "$scenario" --out "$work/$name" -q "${sets[@]}"
  python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); print(s["wall_s"], s["events"])' \
    "$work/$name/summary.json" >>"$work/$name.times"
}

pair() {  # label, then two runs as "name|scenario|override;override"
  local label=$1 a=$2 b=$3
  rm -f "$work"/*.times
  for _ in $(seq "$repeats"); do
    for spec in "$a" "$b"; do
      IFS='|' read -r name scenario overrides <<<"$spec"
      IFS=';' read -r -a list <<<"$overrides"
      run "$name" "$scenario" "${list[@]}"
    done
  done
  python3 - "$work" "$label" "${a%%|*}" "${b%%|*}" <<'PY'
import statistics, sys
work, label, a, b = sys.argv[1:5]
def med(name):
    rows = [line.split() for line in open(f"{work}/{name}.times")]
    return statistics.median(float(r[0]) for r in rows), int(rows[0][1])
(wa, ea), (wb, eb) = med(a), med(b)
print(f"{label}: {a} {wa:.3f} s ({ea} events), {b} {wb:.3f} s ({eb} events), ratio {wa / wb:.2f}")
PY
}

# Peers that drop a section: the scenario with one key removed (neither file includes another).
without() {  # source pointer-path... -> prints the new file
  local src=$1 out="$work/$(basename "$1" .json)_without_$2.json"
  python3 - "$src" "$2" "$out" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
keys = sys.argv[2].split(".")
node = doc
for k in keys[:-1]:
    node = node[k]
del node[keys[-1]]
json.dump(doc, open(sys.argv[3], "w"))
PY
  echo "$out"
}
overload_plain=$(without "$modern/timewarp_overload.json" pipeline.timewarp)
impulse=$(without "$modern/low_persistence_90hz.json" display.persistence)

echo "load: $(uptime)"
pair "staged frames vs one renderer" \
  "staged|$modern/vsync.json|/duration_s=60" \
  "double_buffer|$modern/vsync.json|/duration_s=60;/pipeline={\"type\": \"double_buffer\", \"render\": {\"fixed_ms\": 4}}"
pair "time warp vs swap at retrace (overload)" \
  "compositor|$modern/timewarp_overload.json|/duration_s=20" \
  "no_compositor|$overload_plain|/duration_s=20"
pair "persistence vs impulse display" \
  "persistence|$modern/low_persistence_90hz.json|/duration_s=10" \
  "impulse|$impulse|/duration_s=10"
echo "load: $(uptime)"
