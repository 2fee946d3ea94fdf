#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Core-seconds to D within a total relative error, three ways, side by side.

The headline of docs/efficiency.md ("Plain, control variate and Kolmogorov at
equal error"): on one case (the Fig. 2 case by default), time

  * plain Monte Carlo: `diffusivity --control-variate off`,
  * Monte Carlo with the control variate: `diffusivity` (the default),
  * the Kolmogorov engine: `diffusivity --engine kolmogorov --rel-precision R`,

on one thread, in rounds that alternate the three (so that a busy machine
slows them alike), and extrapolate each Monte Carlo run to the number of
excursions whose 95% half-width plus the step's bias allowance is the target
(the half-width falls like 1/sqrt(N); the corrector's one-off cost is not
scaled). The Kolmogorov engine has no noise: its estimated discretisation
error is its total error, and its time is measured at that target.

  /usr/bin/python3 scripts/validation/time_to_error.py \\
      [--target 0.003] [--bias 0.0008] [--excursions 20000] [--rounds 3] \\
      [--json out.json] build/stickslip
  /usr/bin/python3 scripts/validation/time_to_error.py --bias 0.0008 \\
      -- build/stickslip --dt 0.008      # extra flags for every run

`--bias` is the step's relative bias allowed for at the automatic step (the
Fig. 2 case, relaxation/8: +0.08%, the straight line through docs/validation.md's
table "Choosing the step"; measured +0.06% +- 0.05% against the Kolmogorov
engine; the step before, relaxation/4, took 0.0017). Prints a
Markdown table; `--json` keeps every run.
"""
import argparse
import json
import statistics
import subprocess
import sys


def run(binary, args):
    out = subprocess.run([binary, "diffusivity", "--threads", "1", "--format", "json", *args],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def half_width(est):
    lo, hi = est["ci"]
    return 0.5 * (hi - lo) / abs(est["value"])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binary")
    ap.add_argument("--target", type=float, default=0.003, help="total relative error of D (default 0.003)")
    ap.add_argument("--bias", type=float, default=0.0008, help="the step's relative bias allowed for")
    ap.add_argument("--excursions", type=int, default=20000, help="excursions of each Monte Carlo run")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--json", help="write every run here")
    ap.add_argument("model", nargs="*", help="flags of every run, after the binary: -- build/stickslip --tau 0.1")
    a = ap.parse_args()
    if not 0 <= a.bias < a.target:
        sys.exit("time_to_error.py: --bias must be in [0, --target)")
    runs = {"plain": [], "control variate": [], "kolmogorov": []}
    for r in range(a.rounds):
        seed = ["--seed", str(r + 1)]
        runs["plain"].append(run(a.binary, [*a.model, *seed, "--excursions", str(a.excursions),
                                            "--control-variate", "off"]))
        runs["control variate"].append(run(a.binary, [*a.model, *seed, "--excursions", str(a.excursions)]))
        runs["kolmogorov"].append(run(a.binary, [*a.model, "--engine", "kolmogorov",
                                                 "--rel-precision", str(a.target)]))
    wanted = {"noise only": a.target, "noise + step bias": a.target - a.bias}
    print(f"| method | run | D | relative error | seconds | "
          + " | ".join(f"core-s to {100 * a.target:g}% ({k})" for k in wanted) + " |")
    print("|---|---|---|---|---|" + "---|" * len(wanted))
    for name, js in runs.items():
        seconds = statistics.median(j["work"]["seconds"] for j in js)
        d = statistics.median(j["diffusivity"]["value"] for j in js)
        if name == "kolmogorov":
            err = statistics.median(j["diffusivity"]["error"] / j["diffusivity"]["value"] for j in js)
            cells = [f"{seconds:.3g}" for _ in wanted]
            print(f"| {name} | rel-precision {a.target:g} | {d:.6g} | {100 * err:.3g}% (discretisation) | "
                  f"{seconds:.3g} | " + " | ".join(cells) + " |")
            continue
        hw = statistics.median(half_width(j["diffusivity"]) for j in js)
        fixed = statistics.median(j["work"].get("corrector_seconds", 0.0) for j in js)
        cells = [f"{fixed + (seconds - fixed) * (hw / h) ** 2:.3g}" for h in wanted.values()]
        print(f"| {name} | {a.excursions} excursions | {d:.6g} | {100 * hw:.3g}% (95% half-width) | "
              f"{seconds:.3g} | " + " | ".join(cells) + " |")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(runs, f, indent=1)


if __name__ == "__main__":
    main()
