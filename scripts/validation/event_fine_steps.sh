#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The event scheme at every step a user may choose (docs/validation.md, "The
# event scheme at fine steps"): from its automatic step down to dt/tau = 1e-5
# (white noise: dt' = 1e-5), on drag-free and driven cases, against the
# resolvent scheme at the same step, the PDMP at a fine grid and (white noise)
# the exact quadrature. Each point is one `density` run (D, M0, E[t1], P(V = 0)
# and E[V^2] from the same excursions; white noise: `diffusivity`, whose event
# scheme has no density), seed 1, with as many excursions as a budget of
# STEPS steps allows (at most 2e5): the finest steps get the fewest, so their
# errors are the widest, and the tables print them. Measured: under 40 minutes
# on 2 cores at the default budget, 6e8, while two builds shared the machine.
# Prints markdown tables; the runs are kept in OUT and not redone.
#
# Usage: scripts/validation/event_fine_steps.sh [OUT]   (STEPS=6e8 by default)
set -euo pipefail
cd "$(dirname "$0")/../.."
OUT=${1:-build/validation-event-fine}
B=${STICKSLIP_BIN:-build/stickslip}
STEPS=${STEPS:-6e8}
mkdir -p "$OUT"
exec /usr/bin/python3 - "$OUT" "$B" "$STEPS" <<'PY'
import json, math, os, subprocess, sys

out, exe, budget = sys.argv[1], sys.argv[2], float(sys.argv[3])
# name: (flags, tau [s], E[t1] estimate [s] for sizing, sample-dt [s], velocity range, pdmp grid or None)
unit = "--friction 1 --noise 1"
cases = {
    "dry, tau' = 1": (f"{unit} --tau 1 --relaxation inf --bias 0", 1.0, 10.5, 0.01, "-8,8", 0.0625),
    "dry, tau' = 0.1": (f"{unit} --tau 0.1 --relaxation inf --bias 0", 0.1, 1.2, 0.005, "-8,8", 0.125),
    "dry, tau' = 0.01": (f"{unit} --tau 0.01 --relaxation inf --bias 0", 0.01, 2.0, 0.005, "-8,8", None),
    "bias 0.3, tau' = 1": (f"{unit} --tau 1 --relaxation inf --bias 0.3", 1.0, 12.0, 0.01, "-8,12", 0.0625),
    "drag 0.5, tau' = 1": (f"{unit} --tau 1 --relaxation 0.5 --bias 0", 1.0, 10.5, 0.01, "-6,6", 0.0625),
    "Fig. 2 (defaults)": ("", 0.5, 8.0, 0.01, "-0.5,0.5", 0.0625),
    "driven (noise 3, tau 0.1 s)": ("--noise 3 --tau 0.1 --relaxation 0.067 --bias 2", 0.1, 3.0, 0.002, "-0.5,1", 0.125),
}
ratios = [None, 1e-2, 1e-3, 1e-4, 1e-5]  # None: --dt auto
white = {
    "white, dry": (f"{unit} --tau 0 --relaxation inf --bias 0", 2.0),
    "white, drag 0.2, bias 0.3": (f"{unit} --tau 0 --relaxation 0.2 --bias 0.3", 2.0),
}
white_steps = [None, 1e-3, 1e-4, 1e-5]
white_budget = budget / 5  # the white step is slower per step


def excursions(dt, t1, steps):
    return int(max(100, min(200000, steps * dt / t1))) if dt else 200000


def run(name, argv):
    path = os.path.join(out, name + ".json")
    if not (os.path.exists(path) and os.path.getsize(path) > 0):
        # The guard is raised: at dt = 1e-7 s one excursion in a few hundred of
        # the tau' = 0.01 case lasts more than 2e8 steps (20 s, ten times the
        # mean), and none may be dropped here (each run's "capped" is 0).
        res = subprocess.run([exe] + argv + ["--seed", "1", "--format", "json", "--quiet", "--max-steps", "4e9",
                                             "--output", path],
                             capture_output=True, text=True)
        if res.returncode != 0:
            sys.exit(f"{name}: {res.stderr.strip()}")
    j = json.load(open(path))
    if j.get("capped", 0):
        sys.exit(f"{name}: {j['capped']} excursions capped")
    return j


def quantities(j):
    q = {k: (j[k]["value"], j[k].get("error", 0.0)) for k in ("diffusivity", "mobility", "mean_duration")}
    if "histogram" in j:
        q["p0"] = (j["stuck_probability"]["value"], j["stuck_probability"]["error"])
        m, v = j["mean"]["value"], j["variance"]["value"]
        q["v2"] = (v + m * m, j["variance"]["error"])
    return q


def z(a, b):
    se = math.hypot(a[1], b[1])
    return (a[0] - b[0]) / se if se > 0 else float("nan")


def cell(a, ref):
    return f"{a[0]:.4g} ± {a[1]:.2g} ({z(a, ref):+.1f})"


def slug(s):
    return "".join(c if c.isalnum() else "_" for c in s)


keys = [("diffusivity", "D"), ("mobility", "M0"), ("mean_duration", "E[t1]"), ("p0", "P(V = 0)"), ("v2", "E[V^2]")]
worst = {}
for case, (flags, tau, t1, sample, rng, grid) in cases.items():
    base = flags.split() + ["--range", rng, "--sample-dt", str(sample)]
    ref = quantities(run(slug(case) + "_event_auto", ["density"] + base + ["--excursions", "200000"]))
    refs = {"event at dt auto (2e5)": ref}
    if grid:
        pd = quantities(run(slug(case) + f"_pdmp_{grid}", ["density", "--engine", "pdmp", "--grid", str(grid)] + base +
                            ["--excursions", str(excursions(1.0, t1, budget / 20))]))
        refs[f"PDMP, grid {grid}"] = pd
    print(f"\n#### {case}: `{flags or '(defaults)'}`\n")
    print("Each cell: value ± standard error (z against the reference row of the same quantity: the event scheme "
          "at its automatic step with 2e5 excursions; the resolvent rows also give z against the event row at "
          "the same step in the last column).\n")
    print("| run | dt [s] | dt/tau | excursions | " + " | ".join(k[1] for k in keys) + " | resolvent - event, max abs z |")
    print("|---|---|---|---|" + "---|" * len(keys) + "---|")
    for label, q in refs.items():
        n = "200000" if "auto" in label else ""
        print(f"| {label} | | | {n} | " + " | ".join(f"{q[k][0]:.4g} ± {q[k][1]:.2g}" if k in q else "" for k, _ in keys) + " | |")
    for r in ratios[1:]:
        dt = r * tau
        n = excursions(dt, t1, budget)
        ev = quantities(run(slug(case) + f"_event_{r:g}", ["density"] + base + ["--scheme", "event", "--dt", f"{dt:g}",
                                                                                  "--excursions", str(n)]))
        rs = quantities(run(slug(case) + f"_resolvent_{r:g}", ["density"] + base + ["--scheme", "resolvent", "--dt",
                                                                                      f"{dt:g}", "--excursions", str(n)]))
        zs = [abs(z(ev[k], rs[k])) for k, _ in keys]
        for (k, _), zk in zip(keys, zs):
            # E[t1] and P(V = 0) carry the resolvent step's own O(dt) part
            # (it sees a level or a landing only at a step's end).
            cls = "moments" if k in ("diffusivity", "mobility", "v2") else ("timing, fine" if r < 1e-3 else
                                                                          "timing, coarse")
            worst[cls] = max(worst.get(cls, 0.0), zk)
        print(f"| event | {dt:g} | {r:g} | {n} | " + " | ".join(cell(ev[k], ref[k]) for k, _ in keys) + " | |")
        print(f"| resolvent | {dt:g} | {r:g} | {n} | " + " | ".join(cell(rs[k], ref[k]) for k, _ in keys) +
              f" | {max(zs):.1f} |")

for case, (flags, t1) in white.items():
    ex = json.loads(subprocess.run([exe, "analytic"] + flags.replace("--tau 0", "").split() + ["--format", "json"],
                                   capture_output=True, text=True, check=True).stdout)
    exact = {k: (ex[k]["value"] if isinstance(ex[k], dict) else ex[k], 0.0) for k in ("diffusivity", "mobility")}
    print(f"\n#### {case}: `{flags}`\n")
    print("Each cell: value ± standard error (z against the exact quadrature; E[t1] against the event scheme at its "
          "automatic step). The white-noise event scheme has no density (refused), so P(V = 0) = 0 and E[V^2] are "
          "not in this table.\n")
    print("| run | dt [s] | excursions | D | M0 | E[t1] |")
    print("|---|---|---|---|---|---|")
    print(f"| exact quadrature | | | {exact['diffusivity'][0]:.5g} | {exact['mobility'][0]:.5g} | |")
    auto = quantities(run(slug(case) + "_event_auto", ["diffusivity"] + flags.split() + ["--scheme", "event",
                                                                                        "--excursions", "200000"]))
    print(f"| event, dt auto | auto | 200000 | {cell(auto['diffusivity'], exact['diffusivity'])} | "
          f"{cell(auto['mobility'], exact['mobility'])} | {auto['mean_duration'][0]:.4g} ± {auto['mean_duration'][1]:.2g} |")
    for dt in white_steps[1:]:
        n = excursions(dt, t1, white_budget)
        for scheme in ("event", "resolvent"):
            q = quantities(run(slug(case) + f"_{scheme}_{dt:g}", ["diffusivity"] + flags.split() + [
                "--scheme", scheme, "--dt", f"{dt:g}", "--excursions", str(n)]))
            worst["white D against exact"] = max(worst.get("white D against exact", 0.0),
                                                 abs(z(q["diffusivity"], exact["diffusivity"])))
            print(f"| {scheme} | {dt:g} | {n} | {cell(q['diffusivity'], exact['diffusivity'])} | "
                  f"{cell(q['mobility'], exact['mobility'])} | {cell(q['mean_duration'], auto['mean_duration'])} |")
print("\nLargest |z| between the schemes at one step: D, M0 and E[V^2] "
      f"{worst['moments']:.1f}; E[t1] and P(V = 0) {worst['timing, fine']:.1f} below dt/tau = 1e-3 and "
      f"{worst['timing, coarse']:.1f} at 1e-3 and above (the resolvent's O(dt) part); white noise, D of either "
      f"scheme against the exact value: {worst['white D against exact']:.1f}")
PY
