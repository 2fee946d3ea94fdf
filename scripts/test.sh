#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs what is missing, builds, and runs the whole test suite.
#
#   bash scripts/test.sh               # all tests
#   bash scripts/test.sh -L cli        # extra args go to ctest (labels: unit,
#                                      # statistical, cli, packaging)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/build.sh

BUILD_DIR="${STICKSLIP_BUILD_DIR:-build}"
ctest --test-dir "$BUILD_DIR" --output-on-failure -j2 "$@"
