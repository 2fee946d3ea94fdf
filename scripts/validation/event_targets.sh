#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The event scheme's accuracy targets (docs/validation.md, "The event scheme
# against its targets"), each against a reference the scheme did not produce:
#  * pure dry friction, tau' = 0.1 and 1 (friction = noise = 1): the event
#    scheme at dt' = 1e-2 (and 0.5 for tau' = 0.1, dt >> tau) against the
#    resolvent step at dt' = 1e-4 (tau' = 0.1; its law says -0.4%) and 1e-3
#    (tau' = 1; +0.04%);
#  * tau = 1e-2 s, friction 3.84, noise 1: the stuck fraction and Var(V) of the
#    event scheme at dt = 1e-3 s against the resolvent step at 1e-4, 5e-5 and
#    2.5e-5 s, extrapolated linearly to dt -> 0.
# 1e6 excursions per run, seed 1, 2 threads; about 12 minutes on 2 cores.
# Usage: scripts/validation/event_targets.sh [OUT]; prints what it measured.
set -euo pipefail
cd "$(dirname "$0")/../.."
OUT=${1:-build/validation-event-targets}
B=${STICKSLIP_BIN:-build/stickslip}
mkdir -p "$OUT"
run() { local name=$1; shift; [ -s "$OUT/$name.json" ] || "$B" "$@" --excursions 1000000 --seed 1 --format json --quiet > "$OUT/$name.json"; }
dry=(--friction 1 --noise 1 --relaxation inf --bias 0)
run tau0.1_event_0.01 diffusivity "${dry[@]}" --tau 0.1 --scheme event --dt 0.01
run tau0.1_event_0.5 diffusivity "${dry[@]}" --tau 0.1 --scheme event --dt 0.5
run tau0.1_resolvent_1e-4 diffusivity "${dry[@]}" --tau 0.1 --dt 1e-4
run tau1_event_0.01 diffusivity "${dry[@]}" --tau 1 --scheme event --dt 0.01
run tau1_resolvent_1e-3 diffusivity "${dry[@]}" --tau 1 --dt 1e-3
st=(--friction 3.84 --noise 1 --tau 0.01 --relaxation inf --bias 0 --bins 4)
run stuck_event_1e-3 density "${st[@]}" --scheme event --dt 1e-3
for dt in 1e-4 5e-5 2.5e-5; do run "stuck_resolvent_$dt" density "${st[@]}" --dt $dt; done
/usr/bin/python3 - "$OUT" <<'PY'
import json, sys
out = sys.argv[1]
def load(n): return json.load(open(f"{out}/{n}.json"))
for n in ["tau0.1_event_0.01", "tau0.1_event_0.5", "tau0.1_resolvent_1e-4", "tau1_event_0.01", "tau1_resolvent_1e-3"]:
    j = load(n)
    D, M = j["diffusivity"], j["mobility"]
    print(f"{n}: D {D['value']:.5g} +- {D['error']:.2g}, M0 {M['value']:.3g} +- {M['error']:.2g}, "
          f"E[t1] {j['mean_duration']['value']:.5g} +- {j['mean_duration']['error']:.2g}, {j['work']['seconds']:.1f} s")
for n in ["stuck_event_1e-3", "stuck_resolvent_1e-4", "stuck_resolvent_5e-5", "stuck_resolvent_2.5e-5"]:
    j = load(n)
    print(f"{n}: P(stuck) {j['stuck_probability']['value']:.5f} +- {j['stuck_probability']['error']:.2g}, var {j['variance']['value']:.5g} +- "
          f"{j['variance']['error']:.2g}, {j['work']['seconds']:.1f} s")
PY
