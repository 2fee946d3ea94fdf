#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Reproduces the measured numbers of docs/validation.md (about 9 min on 2 cores):
# discretisation convergence of D on the Fig. 2/4 case (dt for the inclusion
# engine, grid for the PDMP), the white-noise dt convergence against the exact
# quadrature, and brute force against long excursions. Each run is one
# `stickslip` call with a fixed seed, saved as JSON under $OUT; the tables are
# printed by summarize.py. Usage: scripts/validation/convergence.sh [OUT]
set -euo pipefail
cd "$(dirname "$0")/../.."
OUT=${1:-build/validation}
B=${STICKSLIP_BIN:-build/stickslip}
mkdir -p "$OUT"
run() { local name=$1; shift; [ -s "$OUT/$name.json" ] || "$B" "$@" --format json --quiet > "$OUT/$name.json"; }
nd=(--friction 1 --noise 1 --relaxation inf --bias 0)
for dt in 1e-3 3e-4 1e-4; do run "incl_$dt" diffusivity --dt $dt --excursions 20000 --seed 1; done
for g in 0.25 0.125 0.0625; do run "pdmp_$g" diffusivity --engine pdmp --grid $g --excursions 100000 --seed 1; done
for dt in 1e-2 3e-3 1e-3; do
  run "white_dry_$dt" diffusivity "${nd[@]}" --tau 0 --dt $dt --excursions 400000 --seed 1
  run "white_rb_$dt" diffusivity --friction 1 --noise 1 --tau 0 --relaxation 0.2 --bias 0.3 --dt $dt --excursions 400000 --seed 1
done
run wd_1e-2_s2 diffusivity "${nd[@]}" --tau 0 --dt 1e-2 --excursions 2000000 --seed 2
run wd_1e-2_s3 diffusivity "${nd[@]}" --tau 0 --dt 1e-2 --excursions 2000000 --seed 3
run wd_1e-3_s4 diffusivity "${nd[@]}" --tau 0 --dt 1e-3 --excursions 1000000 --seed 4
run tiny_tau_1e-3 diffusivity "${nd[@]}" --tau 1e-4 --dt 1e-3 --excursions 100000 --seed 1
drv=(--relaxation 0.067 --bias 2.0 --friction 3.84 --noise 3 --tau 0.1 --engine pdmp)
for t in 10 20; do
  run "bf_fig2_$t" bruteforce --engine pdmp --time $t --trajectories 40000 --seed 1
  run "bf_drv_$t" bruteforce "${drv[@]}" --time $t --trajectories 20000 --seed 1
done
for e in renewal paper; do run "le_drv_$e" diffusivity "${drv[@]}" --excursions 40000 --estimator $e --seed 1; done
/usr/bin/python3 "$(dirname "$0")/summarize.py" "$OUT"
