#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The event scheme at coarse steps (docs/validation.md, "The event scheme at
# coarse steps"): the measured reach behind the step checks of
# src/driver/step_check.cpp. Each row is one `diffusivity` run of 1e5 excursions,
# seed 1, against a reference the row did not produce (coloured noise: the
# event scheme at a step of tau/10 or finer with the same excursions count;
# white noise: the exact quadrature of `stickslip analytic`). Steps the checks
# refuse print as "refused". About 3 minutes on 2 cores. Prints a markdown
# table.
#
# Usage: scripts/validation/event_coarse_steps.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
B=${STICKSLIP_BIN:-build/stickslip}
exec /usr/bin/python3 - "$B" <<'PY'
import json, math, subprocess, sys

exe = sys.argv[1]
unit = "--friction 1 --noise 1"
# name: (flags, tau [s] or 0, scale name, scale [s], reference step [s] or None for the quadrature, steps [s])
cases = [
    ("Fig. 2 (defaults)", "", 0.5, "tau", 0.5, 0.01, [0.1, 0.3, 1, 3, 10, 100]),
    ("dry, tau' = 0.1", f"{unit} --tau 0.1 --relaxation inf --bias 0", 0.1, "tau", 0.1, 0.01, [0.1, 0.3, 1, 3]),
    ("white, bias 0.3, no drag", f"{unit} --tau 0 --relaxation inf --bias 0.3", 0, "T_f", 1.0, None, [0.25, 0.5, 1, 2]),
    ("white, relaxation 0.2, bias 0.3", f"{unit} --tau 0 --relaxation 0.2 --bias 0.3", 0, "relaxation", 0.2, None,
     [0.05, 0.1, 0.2, 0.4, 3]),
]


def run(argv):
    r = subprocess.run([exe, "diffusivity", "--scheme", "event", "--excursions", "100000", "--seed", "1",
                        "--format", "json", "--quiet"] + argv, capture_output=True, text=True)
    if r.returncode == 2:
        return None
    if r.returncode != 0:
        sys.exit(f"{argv}: {r.stderr.strip()}")
    j = json.loads(r.stdout)
    return {k: (j[k]["value"], j[k].get("error", 0.0)) for k in ("diffusivity", "mobility", "mean_duration")}


def cell(a, ref):
    se = math.hypot(a[1], ref[1])
    # A relative difference only where the reference is known to be nonzero
    # (the symmetric case's M0 is zero up to its noise).
    rel = f"{100 * (a[0] / ref[0] - 1):+.1f}%, " if abs(ref[0]) > 5 * se else ""
    return f"{a[0]:.4g} ± {a[1]:.2g} ({rel}z = {(a[0] - ref[0]) / se:+.1f})"


print("| case | reference | dt [s] | dt / scale | D | M0 | E[t1] [s] |")
print("|---|---|---|---|---|---|---|")
for name, flags, tau, scale_name, scale, ref_dt, steps in cases:
    if ref_dt:
        ref = run(flags.split() + ["--dt", str(ref_dt)])
        label = f"event, dt = {ref_dt:g} s"
        print(f"| {name} | {label} | {ref_dt:g} | {ref_dt / scale:g} {scale_name} | {ref['diffusivity'][0]:.4g} ± "
              f"{ref['diffusivity'][1]:.2g} | {ref['mobility'][0]:.4g} ± {ref['mobility'][1]:.2g} | "
              f"{ref['mean_duration'][0]:.4g} ± {ref['mean_duration'][1]:.2g} |")
    else:
        ex = json.loads(subprocess.run([exe, "analytic"] + flags.replace("--tau 0", "").split() + ["--format", "json"],
                                       capture_output=True, text=True, check=True).stdout)
        ref = {k: (ex[k]["value"] if isinstance(ex[k], dict) else ex[k], 0.0) for k in ("diffusivity", "mobility")}
        label = "exact quadrature"
        print(f"| {name} | {label} | | | {ref['diffusivity'][0]:.5g} | {ref['mobility'][0]:.5g} | |")
    for dt in steps:
        q = run(flags.split() + ["--dt", str(dt)])
        if q is None:
            print(f"| {name} | {label} | {dt:g} | {dt / scale:g} {scale_name} | refused (exit 2) | | |")
            continue
        t1 = cell(q["mean_duration"], ref["mean_duration"]) if "mean_duration" in ref else \
            f"{q['mean_duration'][0]:.4g} ± {q['mean_duration'][1]:.2g}"
        print(f"| {name} | {label} | {dt:g} | {dt / scale:g} {scale_name} | {cell(q['diffusivity'], ref['diffusivity'])} "
              f"| {cell(q['mobility'], ref['mobility'])} | {t1} |")
PY
