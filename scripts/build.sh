#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs missing dependencies, then configures (Release; Ninja when
# available) and builds stickslip with all cores. Fast when already built.
#
#   bash scripts/build.sh            # build dir: build/
#   STICKSLIP_BUILD_DIR=build-x bash scripts/build.sh
#
# Extra arguments are passed to the configure step (e.g. -DSTICKSLIP_NATIVE=ON).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh

BUILD_DIR="${STICKSLIP_BUILD_DIR:-build}"
JOBS="$(nproc 2>/dev/null || getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)"

cache="$BUILD_DIR/CMakeCache.txt"
if [[ ! -f "$cache" ]]; then
  generator=()
  if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
  # MPI support when an MPI compiler is there (install-deps installs Open MPI);
  # the command starts MPI only when launched by mpirun.
  mpi=()
  if command -v mpicxx >/dev/null 2>&1; then mpi=(-DSTICKSLIP_MPI=ON); fi
  # The benchmarks are built too, so that the test suite runs them once (smoke).
  cmake -S . -B "$BUILD_DIR" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DSTICKSLIP_BUILD_BENCH=ON "${mpi[@]}" "$@"
elif [[ $# -gt 0 ]] || ! grep -q '^CMAKE_BUILD_TYPE:[A-Z]*=Release$' "$cache"; then
  # Already configured (with whatever generator it has): only reconfigure when
  # asked to, or when it is not a Release build. Otherwise the build step below
  # re-runs CMake by itself if any CMakeLists.txt changed.
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release "$@"
fi

cmake --build "$BUILD_DIR" --parallel "$JOBS"

# The Python module for Debian's /usr/bin/python3, so that `import stickslip`
# works anywhere: pip (offline) takes the module just built in $BUILD_DIR.
if grep -q '^STICKSLIP_PYTHON:BOOL=ON$' "$BUILD_DIR/CMakeCache.txt" &&
   grep -q '^Python3_EXECUTABLE:FILEPATH=/usr/bin/python3$' "$BUILD_DIR/CMakeCache.txt" &&
   /usr/bin/python3 -m pip --version >/dev/null 2>&1; then
  pip_target=()
  [[ $(id -u) -eq 0 ]] || pip_target=(--user)
  STICKSLIP_CMAKE_BUILD_DIR="$BUILD_DIR" /usr/bin/python3 -m pip install -q --no-build-isolation --no-index \
    --no-deps --break-system-packages --root-user-action=ignore "${pip_target[@]}" .
  echo "build: stickslip Python module installed for /usr/bin/python3"
fi
