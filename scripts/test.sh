#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs what is missing, builds, and runs the whole test suite.
#
#   bash scripts/test.sh               # all tests
#   bash scripts/test.sh -L cli        # extra args go to ctest (labels: unit,
#                                      # statistical, cli, packaging, pip)
#
# A full run (no arguments) also builds every target with clang when clang++
# is on the machine (build-clang/, warnings as errors) and runs the unit tests
# there, so that the tree keeps building with both common compilers (about 8
# minutes more on 2 cores; STICKSLIP_SKIP_CLANG=1 skips it), and then installs
# the sdist with pip into a fresh venv (ctest -L pip, about 4 minutes on 2
# cores; STICKSLIP_SKIP_PIP=1 skips it).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/build.sh

BUILD_DIR="${STICKSLIP_BUILD_DIR:-build}"
if [[ $# -eq 0 ]]; then
  # The pip install from the sdist (label pip) compiles everything afresh:
  # it runs on its own below, after the rest.
  ctest --test-dir "$BUILD_DIR" --output-on-failure -j2 -LE '^pip$'
else
  ctest --test-dir "$BUILD_DIR" --output-on-failure -j2 "$@"
fi

if [[ $# -eq 0 && -z "${STICKSLIP_SKIP_CLANG:-}" ]] && command -v clang++ >/dev/null 2>&1; then
  CLANG_DIR="${STICKSLIP_CLANG_BUILD_DIR:-build-clang}"
  if [[ ! -f "$CLANG_DIR/CMakeCache.txt" ]]; then
    generator=()
    if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
    CC=clang CXX=clang++ cmake -S . -B "$CLANG_DIR" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
      -DSTICKSLIP_BUILD_BENCH=ON -DCMAKE_CXX_FLAGS=-Werror
  fi
  cmake --build "$CLANG_DIR" --parallel "$(nproc 2>/dev/null || echo 2)"
  ctest --test-dir "$CLANG_DIR" --output-on-failure -j2 -L unit
  echo "test: clang build and unit tests passed ($CLANG_DIR)"
fi

if [[ $# -eq 0 && -z "${STICKSLIP_SKIP_PIP:-}" ]]; then
  ctest --test-dir "$BUILD_DIR" --output-on-failure -L '^pip$'
fi
