#!/usr/bin/env bash
# Set up, build, and run the whole test suite with ctest (long soak runs,
# labelled "soak", only with SOAK=1).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")"
scripts/setup.sh
exclude=(-LE soak)
[ "${SOAK:-0}" = 1 ] && exclude=()
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure -j"$(nproc)" "${exclude[@]}"
