#!/usr/bin/env bash
# Installs latsim's Debian packages if any are missing, then configures and
# builds into build/. Safe to run again: it only does what is not done yet.
#   BUILD_DIR=build  BUILD_TYPE=Release  LATSIM_SANITIZE=OFF  JOBS=$(nproc)
#   TARGET=latsim builds the command alone (the main job); unset: everything, tests included
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

PACKAGES=(g++ cmake make pkg-config git python3 python3-matplotlib
          libglm-dev libeigen3-dev nlohmann-json3-dev catch2 libembree-dev
          libcli11-dev libpng-dev zlib1g-dev libtbb-dev libsqlite3-dev libopenmpi-dev openmpi-bin
          python3-jsonschema
          # The Python module (python/) and its example notebook's test.
          pybind11-dev python3-dev python3-pandas python3-nbclient python3-nbconvert python3-ipykernel
          # The sanitizer and fuzz build of .ci/run: clang with libFuzzer.
          clang libclang-rt-14-dev)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ((${#missing[@]})); then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO=sudo
  echo "setup: installing ${missing[*]}" >&2
  $SUDO apt-get update -qq
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

BUILD_DIR=${BUILD_DIR:-build}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" \
      -DLATSIM_SANITIZE="${LATSIM_SANITIZE:-OFF}" >/dev/null
cmake --build "$BUILD_DIR" -j"${JOBS:-$(nproc)}" ${TARGET:+--target "$TARGET"}
