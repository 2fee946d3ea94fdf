#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The white-noise event scheme against the exact quadrature (docs/validation.md,
# "The event scheme for white noise"): three models (friction = noise = 1;
# pure dry friction, a bias of 0.3, a drag of relaxation 0.2 with that bias),
# each at three steps, the automatic one included, with the resolvent step at
# dt = 0.01 beside them. 1e6 excursions per run, seed 1; about 3 minutes on 2
# cores. Prints a markdown table. Usage: scripts/validation/event_white.sh [OUT]
set -euo pipefail
cd "$(dirname "$0")/../.."
OUT=${1:-build/validation-event-white}
B=${STICKSLIP_BIN:-build/stickslip}
mkdir -p "$OUT"
run() { local name=$1; shift; [ -s "$OUT/$name.json" ] || "$B" diffusivity "$@" --excursions 1000000 --seed 1 --format json --quiet > "$OUT/$name.json"; }
declare -A MODEL=([dry]="--relaxation inf --bias 0" [bias]="--relaxation inf --bias 0.3" [drag]="--relaxation 0.2 --bias 0.3")
declare -A STEPS=([dry]="0.01 auto 0.125" [bias]="0.01 auto 0.125" [drag]="0.01 auto 0.05")
for m in dry bias drag; do
  for dt in ${STEPS[$m]}; do run "${m}_event_$dt" --friction 1 --noise 1 --tau 0 ${MODEL[$m]} --scheme event --dt $dt; done
  run "${m}_resolvent_0.01" --friction 1 --noise 1 --tau 0 ${MODEL[$m]} --dt 0.01
done
/usr/bin/python3 - "$OUT" "$B" <<'PY'
import json, subprocess, sys
out, exe = sys.argv[1], sys.argv[2]
models = {"dry": ("inf", "0"), "bias": ("inf", "0.3"), "drag": ("0.2", "0.3")}
steps = {"dry": ["0.01", "auto", "0.125"], "bias": ["0.01", "auto", "0.125"], "drag": ["0.01", "auto", "0.05"]}
print("| model | scheme | dt | D | vs exact | M0 | vs exact | E[t1] | wall time (2 threads) |")
print("|---|---|---|---|---|---|---|---|---|")
for m, (relax, bias) in models.items():
    ex = json.loads(subprocess.run([exe, "analytic", "--friction", "1", "--noise", "1", "--relaxation", relax,
                                    "--bias", bias, "--format", "json"], capture_output=True, text=True, check=True).stdout)
    d0, m0 = ex["diffusivity"], ex["mobility"]
    d0 = d0["value"] if isinstance(d0, dict) else d0
    m0 = m0["value"] if isinstance(m0, dict) else m0
    for scheme, dts in (("event", steps[m]), ("resolvent", ["0.01"])):
        for dt in dts:
            j = json.load(open(f"{out}/{m}_{scheme}_{dt}.json"))
            D, M, T = j["diffusivity"], j["mobility"], j["mean_duration"]
            def rel(e, x):
                return f"{100 * (e['value'] - x) / x:+.2f}% (z = {(e['value'] - x) / e['error']:+.1f})" if x else f"z = {e['value'] / e['error']:+.1f}"
            print(f"| {m} (relaxation {relax}, bias {bias}) | {scheme} | {j['params']['dt']:g}{' (auto)' if dt == 'auto' else ''} | "
                  f"{D['value']:.5g} ± {D['error']:.2g} | {rel(D, d0)} | {M['value']:.5g} ± {M['error']:.2g} | {rel(M, m0)} | "
                  f"{T['value']:.4f} | {j['work']['seconds']:.1f} s |")
PY
