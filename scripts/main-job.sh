#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The main job: installs what is missing, builds, and computes the diffusivity
# D, the mobility M0 and the mean long-excursion duration E[t1], with 95%
# confidence intervals, for the paper's Fig. 2 parameters (the CLI defaults:
# friction 3.84 m/s^2, noise 5 m^2/s^3, tau 0.5 s, relaxation 0.067 s,
# bias 0.342 m/s^2; inclusion engine, event scheme at its automatic step):
# 1.6e6 excursions, D to about +-0.1% (95%) in about a minute on 2 cores.
#
#   bash scripts/main-job.sh                     # table on stdout
#   bash scripts/main-job.sh --format json       # extra args go to the command
#   STICKSLIP_MAIN_EXCURSIONS=6400000 bash scripts/main-job.sh  # half the interval width
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/build.sh >&2

BUILD_DIR="${STICKSLIP_BUILD_DIR:-build}"
EXCURSIONS="${STICKSLIP_MAIN_EXCURSIONS:-1600000}"
echo "main job: stickslip diffusivity, paper Fig. 2 parameters, $EXCURSIONS long excursions" >&2
exec "$BUILD_DIR/stickslip" diffusivity --excursions "$EXCURSIONS" "$@"
