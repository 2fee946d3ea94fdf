#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Static friction above kinetic friction: the engines against each other
(docs/validation.md, "Static and kinetic friction").

For each case and each ratio Delta_s / Delta, the Kolmogorov engine (no
sampling, its own error estimate) is the reference, and the sampled engines
are compared with it: D, M0 and E[t1] from `diffusivity` (the control variate
on), P(V = 0) from `density`. Each row gives the sampled value, its standard
error and z = (sampled - reference) / sqrt(se^2 + err^2).

Usage (the table of docs/validation.md, about 40 minutes on 2 cores):
    scripts/validation/static_friction.py --bin build/stickslip > static.md
    scripts/validation/static_friction.py --bin build/stickslip --quick   # one case, one ratio
Raw records go to --out (JSON) when given.
"""
import argparse
import json
import math
import subprocess
import sys

# name, model flags (the friction is given so that the static friction is a ratio of it)
CASES = [
    ("dry tau'=1", 1.0, "--friction 1 --noise 1 --tau 1 --relaxation inf --bias 0"),
    ("dry+bias tau'=1", 1.0, "--friction 1 --noise 1 --tau 1 --relaxation inf --bias 0.3"),
    ("Fig. 2", 3.84, "--friction 3.84 --noise 5 --tau 0.5 --relaxation 0.067 --bias 0.342"),
]
RATIOS = [1.2, 1.5, 3.0]
# Beyond this mean excursion time [s] the sampled engines are not run (at
# Delta_s = 3 Delta the Fig. 2 case's static edge is 5 standard deviations of
# the noise out), but the event scheme, the cheapest per unit of time, up to
# EVENT_MAX_MEAN_DURATION.
MAX_MEAN_DURATION = 2.0e4
EVENT_MAX_MEAN_DURATION = 5.0e4


def engines(friction, mean_duration):
    """The sampled engines at their settings: (label, flags, excursions).
    Long excursions (a wide static band: E[t1] of 1e4 s at Delta_s = 3 Delta
    without drag) get fewer excursions and the PDMP a coarser lattice (its
    events come at rate 2/(tau grid)^2)."""
    long = mean_duration > 200.0
    return [
        ("event dt auto", "--scheme event --dt auto", 2000 if long else 20000),
        ("resolvent fine", "--scheme resolvent --dt %g" % (3e-4 if friction > 2 else 1e-3), 1000 if long else 10000),
        ("pdmp grid 0.1", "--engine pdmp --grid 0.1", 400) if long else
        ("pdmp grid 0.025", "--engine pdmp --grid 0.025", 5000),
    ]


def run(binary, args):
    r = subprocess.run([binary, *args.split(), "--format", "json", "--quiet"], capture_output=True, text=True)
    if r.returncode != 0:
        return {"error": r.stderr.strip()}
    return json.loads(r.stdout)


def value(j, key):
    e = j.get(key)
    if not e:
        return None
    return e["value"], e.get("error", 0.0)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", required=True)
    ap.add_argument("--quick", action="store_true", help="the first case at ratio 1.5 only")
    ap.add_argument("--out", help="raw records (JSON)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--no-header", action="store_true", help="rows only (to append to an earlier table)")
    ap.add_argument("--cases", help="indices of the cases to run, e.g. 1,2 (default: all)")
    ap.add_argument("--ratios", help="ratios Delta_s/Delta, e.g. 1.5,3 (default: 1.2,1.5,3)")
    ap.add_argument("--only", help="the sampled engines whose label starts with this, e.g. pdmp (default: all)")
    a = ap.parse_args()
    cases = [CASES[int(i)] for i in a.cases.split(",")] if a.cases else CASES
    ratios = [float(r) for r in a.ratios.split(",")] if a.ratios else RATIOS
    if a.quick:
        cases, ratios = CASES[:1], [1.5]
    records = []
    if not a.no_header:
        print("| case | Delta_s/Delta | engine | D | z | M0 | z | E[t1] | z | P(V=0) | z |")
        print("|---|---|---|---|---|---|---|---|---|---|---|")
    for name, friction, model in cases:
        for ratio in ratios:
            m = "%s --static-friction %.17g" % (model, ratio * friction)
            ref = run(a.bin, "diffusivity --engine kolmogorov " + m)
            rec = {"case": name, "ratio": ratio, "kolmogorov": ref, "sampled": {}}
            if "error" in ref:
                print("| %s | %g | kolmogorov | refused: %s |" % (name, ratio, ref["error"]))
                records.append(rec)
                continue
            keys = [("diffusivity", "diffusivity"), ("mobility", "mobility"), ("mean_duration", "mean_duration"),
                    ("stuck_probability", "stuck_probability")]
            cells = []
            for k, _ in keys:
                v = value(ref, k)
                cells += ["%.6g +- %.2g" % v if v else "-", ""]
            print("| %s | %g | kolmogorov | %s |" % (name, ratio, " | ".join(cells)))
            mean_duration = ref["mean_duration"]["value"]
            chosen = [e for e in engines(friction, mean_duration) if not a.only or e[0].startswith(a.only)]
            limit = lambda label: EVENT_MAX_MEAN_DURATION if label.startswith("event") else MAX_MEAN_DURATION
            skipped = [e[0] for e in chosen if mean_duration > limit(e[0])]
            if skipped:
                print("| %s | %g | %s | skipped: E[t1] = %.3g s (one excursion is that long) |"
                      % (name, ratio, ", ".join(skipped), mean_duration))
            for label, flags, n in chosen:
                if label in skipped:
                    continue
                d = run(a.bin, "diffusivity %s %s --excursions %d --seed %d" % (m, flags, n, a.seed))
                p = run(a.bin, "density %s %s --excursions %d --bins 4 --seed %d" % (m, flags, max(n // 4, 1000),
                                                                                    a.seed + 1))
                rec["sampled"][label] = {"diffusivity": d, "density": p}
                cells = []
                for k, _ in keys:
                    src = p if k == "stuck_probability" else d
                    v, r = value(src, k) if "error" not in src else None, value(ref, k)
                    if not v or not r:
                        cells += ["-", ""]
                        continue
                    z = (v[0] - r[0]) / math.sqrt(v[1] ** 2 + r[1] ** 2) if v[1] > 0 else float("nan")
                    cells += ["%.6g +- %.2g" % v, "%+.1f" % z]
                print("| %s | %g | %s | %s |" % (name, ratio, label, " | ".join(cells)))
                sys.stdout.flush()
            records.append(rec)
    if a.out:
        with open(a.out, "w") as f:
            json.dump(records, f)


if __name__ == "__main__":
    main()
