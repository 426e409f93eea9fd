#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time from the shipped seeds.
#   run_fuzz.sh TARGET SECONDS WORK_DIR REGRESSIONS_DIR SEED...
# New corpus entries go to WORK_DIR/corpus (kept between runs); a crashing,
# hanging or leaking input is written to WORK_DIR/artifacts and fails the
# test: copy it into REGRESSIONS_DIR once the defect is fixed.
set -euo pipefail
target=$1 seconds=$2 work=$3 regressions=$4
shift 4
mkdir -p "$work/corpus" "$work/artifacts"
# -timeout: an input taking this long is a hang; -rss_limit_mb: runaway memory.
"$target" "$work/corpus" "$regressions" "$@" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2560 \
  -max_len=65536 -print_final_stats=1 -artifact_prefix="$work/artifacts/" 2>"$work/log.txt" || {
  tail -n 60 "$work/log.txt"
  echo "fuzz: $(basename "$target") found an input that fails: see $work/artifacts" >&2
  exit 1
}
grep -E "^stat::(number_of_executed_units|average_exec_per_sec|new_units_added)|INFO: .*corp" "$work/log.txt" | tail -n 5
