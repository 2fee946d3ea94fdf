#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Stop-rule check (docs/theory.md, section 6), outside the CI suite because it is slow:
# pure dry friction, tau' = 0.1, dt' = 1e-3 (nondimensional: friction = noise = 1).
# Compares the long-excursion D with the bridge rule (Q) and the stuck rule (P)
# against the rule-free brute-force estimator at two horizons, extrapolated in
# 1/t:  D = (t2 D_t2 - t1 D_t1) / (t2 - t1).
#
# Usage: scripts/validation/stop_rule_check.sh [N_excursions] [N_trajectories] [t1] [t2]
# Seeds are SEED_BASE+1 (bridge), +2 (stuck), +3, +4 (brute force); SEED_BASE
# defaults to 100. docs/validation.md used `20000000 2000000 10 20` with
# SEED_BASE=300 (about 20 min on 2 cores). Output: $STICKSLIP_VALIDATION_OUT
# (default build/validation).
set -euo pipefail
cd "$(dirname "$0")/../.."
N_LE=${1:-4000000}
N_BF=${2:-400000}
T1=${3:-10}
T2=${4:-20}
B=${STICKSLIP_BIN:-build/stickslip}
S=${SEED_BASE:-100}
OUT=${STICKSLIP_VALIDATION_OUT:-build/validation}
mkdir -p "$OUT"
common=(--friction 1 --noise 1 --tau 0.1 --relaxation inf --bias 0 --dt 1e-3 --format json --quiet)
$B diffusivity "${common[@]}" --excursions "$N_LE" --stop-rule bridge --seed $((S + 1)) > "$OUT/sr_bridge.json"
$B diffusivity "${common[@]}" --excursions "$N_LE" --stop-rule stuck --seed $((S + 2)) > "$OUT/sr_stuck.json"
$B bruteforce "${common[@]}" --trajectories "$N_BF" --time "$T1" --seed $((S + 3)) > "$OUT/sr_bf_t1.json"
$B bruteforce "${common[@]}" --trajectories "$N_BF" --time "$T2" --seed $((S + 4)) > "$OUT/sr_bf_t2.json"
/usr/bin/python3 - "$OUT" "$T1" "$T2" <<'PY'
import json, math, sys
out, t1, t2 = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
ld = lambda n: json.load(open(f"{out}/{n}.json"))
b1, b2 = ld("sr_bf_t1")["diffusivity"], ld("sr_bf_t2")["diffusivity"]
ext = (t2 * b2["value"] - t1 * b1["value"]) / (t2 - t1)
ext_se = math.hypot(t2 * b2["error"], t1 * b1["error"]) / (t2 - t1)
print(f"brute force D_t1 = {b1['value']:.5g} +- {b1['error']:.2g} (t' = {t1:g}), D_t2 = {b2['value']:.5g} +- {b2['error']:.2g} (t' = {t2:g})")
print(f"extrapolated in 1/t: D = {ext:.5g} +- {ext_se:.2g}")
print("| rule | D' | stderr | vs extrapolated brute force | z |")
print("|---|---|---|---|---|")
for name in ("bridge", "stuck"):
    d = ld(f"sr_{name}")["diffusivity"]
    diff = d["value"] / ext - 1
    z = (d["value"] - ext) / math.hypot(d["error"], ext_se)
    print(f"| {name} | {d['value']:.5g} | {d['error']:.2g} | {100*diff:+.2f}% | {z:+.2f} |")
PY
