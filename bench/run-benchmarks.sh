#!/usr/bin/env bash
# run-benchmarks.sh -- PHOLD: latsim's kernel against its peers, in one go.
#
# For both shapes (1024 LPs x 16 events, 64 LPs x 16 events) this script
#   1. validates: every program at the same end time must report the same
#      `events=` and `check=` (the per-LP checksum) as the bare loop;
#   2. times RUNS runs of each program, round-robin so that load changes on
#      the machine hit all of them alike, and takes medians;
#   3. prints events/s and the ratios of ours to the bare priority_queue loop,
#      to the better SystemC mode (lp or token) and to SimPy.
#
# Peers come from PEERS_DIR (default ../shared/bench next to the repository)
# and are built with g++ -O2 like its run-peers.sh does. Our program is
# $PHOLD, default build/phold, built with CMake if missing.
#
# Knobs (environment): RUNS=3 PEERS_DIR BUILD_DIR PHOLD PYTHON=/usr/bin/python3
# and per-shape end times: END_OURS_D END_BASE_D END_SC_D END_PY_D (default
# shape) and END_OURS_S END_BASE_S END_SC_S END_PY_S (small shape), sized for
# about 1-3 s per run on an idle machine: the whole script takes ~2 min idle,
# ~6 min when other jobs keep both cores of this VM busy.
set -euo pipefail

HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
ROOT=$(cd "$HERE/.." && pwd)
PEERS=${PEERS_DIR:-$ROOT/../shared/bench}
BUILD=${BUILD_DIR:-${TMPDIR:-/tmp}/latsim-phold-bench}
PY=${PYTHON:-/usr/bin/python3}
PHOLD=${PHOLD:-$ROOT/build/phold}
RUNS=${RUNS:-3}

END_OURS_D=${END_OURS_D:-1500} END_BASE_D=${END_BASE_D:-1500} END_SC_D=${END_SC_D:-400} END_PY_D=${END_PY_D:-40}
END_OURS_S=${END_OURS_S:-40000} END_BASE_S=${END_BASE_S:-40000} END_SC_S=${END_SC_S:-12000} END_PY_S=${END_PY_S:-1500}
VALIDATE_D=150
VALIDATE_S=6000

# ---- 1. build ----------------------------------------------------------------
if [ ! -x "$PHOLD" ]; then
  echo "building $PHOLD" >&2
  cmake -S "$ROOT" -B "$ROOT/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$ROOT/build" --target phold -j"$(nproc)" >/dev/null
fi
if [ ! -f "$PEERS/phold_baseline.cpp" ]; then
  echo "peer sources not found in $PEERS (set PEERS_DIR)" >&2
  exit 1
fi
mkdir -p "$BUILD"
g++ -std=c++20 -O2 -ffp-contract=off -o "$BUILD/phold_baseline" "$PEERS/phold_baseline.cpp"
# C++17: Debian's libsystemc 2.3.4 is built as C++17 and checks it at link time.
g++ -std=c++17 -O2 -ffp-contract=off -o "$BUILD/phold_systemc" "$PEERS/phold_systemc.cpp" -lsystemc
"$PY" -c 'import SimPy.Simulation' 2>/dev/null || {
  echo "SimPy 2 not importable by $PY (Debian package python3-simpy)" >&2
  exit 1
}

# run_prog LPS END CMD... -> "events wall_s events_per_s check"
run_prog() {
  local lps=$1 end=$2
  shift 2
  local out check
  out=$("$@" --lps "$lps" --epl 16 --seed 1 --mean 1.0 --lookahead 0.1 --end "$end" 2>"$BUILD/stderr.txt") || {
    cat "$BUILD/stderr.txt" >&2
    echo "FAILED: $*" >&2
    exit 1
  }
  check=$(grep -o 'check=[0-9a-f]*' "$BUILD/stderr.txt" | tail -n1 | cut -d= -f2)
  echo "$out" | awk -v c="$check" '{
    for (i = 1; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] }
    print v["events"], v["wall_s"], v["events_per_s"], c }'
}

median() { sort -g | awk '{a[NR] = $1} END { if (NR % 2) print a[(NR + 1) / 2]; else print (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }

LABELS=(latsim baseline systemc-lp systemc-token simpy)
command_of() {
  case $1 in
    latsim) echo "$PHOLD" ;;
    baseline) echo "$BUILD/phold_baseline" ;;
    systemc-lp) echo "$BUILD/phold_systemc --mode lp" ;;
    systemc-token) echo "$BUILD/phold_systemc --mode token" ;;
    simpy) echo "$PY $PEERS/phold_simpy.py" ;;
  esac
}

echo "machine: $(nproc) cpu, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'); load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "versions: $(g++ --version | head -n1); SystemC $(dpkg-query -W -f='${Version}' libsystemc-dev 2>/dev/null || echo '?');" \
     "SimPy $(dpkg-query -W -f='${Version}' python3-simpy 2>/dev/null || echo '?'); $($PY --version 2>&1)"
echo "latsim: $PHOLD ($(git -C "$ROOT" rev-parse --short=12 HEAD 2>/dev/null || echo 'no git'))"

# shape NAME LPS VALIDATE_END END_OURS END_BASE END_SC END_PY
shape() {
  local name=$1 lps=$2 vend=$3
  declare -A END=([latsim]=$4 [baseline]=$5 [systemc-lp]=$6 [systemc-token]=$6 [simpy]=$7)
  echo
  echo "== $name: $lps LPs x 16 events ($((lps * 16)) pending), runs=$RUNS =="
  echo "validation at end=$vend:"
  local ref="" label res ev ck
  for label in baseline latsim systemc-lp systemc-token simpy; do
    # shellcheck disable=SC2046
    res=$(run_prog "$lps" "$vend" $(command_of "$label"))
    read -r ev _ _ ck <<<"$res"
    printf '  %-14s events=%s check=%s\n' "$label" "$ev" "$ck"
    if [ -z "$ref" ]; then
      ref="$ev $ck"
    elif [ "$ref" != "$ev $ck" ]; then
      echo "VALIDATION FAILED: $label disagrees with baseline ($ref)" >&2
      exit 1
    fi
  done
  echo "  OK: identical committed events and per-LP checksum"

  declare -A RATES EVENTS
  local r rate wall
  for ((r = 1; r <= RUNS; r++)); do
    for label in "${LABELS[@]}"; do
      # shellcheck disable=SC2046
      res=$(run_prog "$lps" "${END[$label]}" $(command_of "$label"))
      read -r ev wall rate _ <<<"$res"
      RATES[$label]="${RATES[$label]:-} $rate"
      EVENTS[$label]=$ev
      echo "  run $r $label end=${END[$label]} events=$ev wall_s=$wall events_per_s=$rate" >&2
    done
  done
  declare -A MED
  printf '%-14s %8s %12s %14s %9s\n' program end events events_per_s ns/event
  for label in "${LABELS[@]}"; do
    MED[$label]=$(printf '%s\n' ${RATES[$label]} | median)
    awk -v l="$label" -v e="${END[$label]}" -v n="${EVENTS[$label]}" -v r="${MED[$label]}" \
      'BEGIN { printf "%-14s %8s %12d %14.0f %9.1f\n", l, e, n, r, 1e9 / r }'
  done
  awk -v o="${MED[latsim]}" -v b="${MED[baseline]}" -v lp="${MED[systemc-lp]}" -v tk="${MED[systemc-token]}" \
      -v py="${MED[simpy]}" 'BEGIN {
    sc = (lp > tk) ? lp : tk
    best = (lp > tk) ? "lp" : "token"
    rb = o / b; rs = o / sc; rp = o / py
    printf "ratio latsim/baseline      %6.2f  (must >= 0.67, target >= 1.0)%s\n", rb, ((rb >= 0.67) ? "" : "  BELOW MUST")
    printf "ratio latsim/SystemC best  %6.2f  (must >= 2, target >= 3; best = %s)%s\n", rs, best, ((rs >= 2) ? "" : "  BELOW MUST")
    printf "ratio latsim/SimPy         %6.2f  (must >= 15, target >= 25)%s\n", rp, ((rp >= 15) ? "" : "  BELOW MUST")
  }'
}

shape "default" 1024 "$VALIDATE_D" "$END_OURS_D" "$END_BASE_D" "$END_SC_D" "$END_PY_D"
shape "small" 64 "$VALIDATE_S" "$END_OURS_S" "$END_BASE_S" "$END_SC_S" "$END_PY_S"
echo
echo "(medians of $RUNS runs; load average at the end $(cut -d' ' -f1-3 /proc/loadavg))"
