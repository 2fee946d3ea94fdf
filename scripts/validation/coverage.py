#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Interval coverage study (docs/validation.md, "Interval coverage").

For each case and each sample size N (excursions, or trajectories for brute
force), R independent runs of the CLI (one process per run, --threads 1, seeds
first_seed + 1000000 j + i for the j-th size and i < R, so runs never share
streams) report an estimate, its standard error and its interval. The
reference is the pooled estimate over every run of the case, both sizes: for a
renewal-reward ratio sum_i R_i T_i / sum_i T_i with T_i = N_i E[t1]_i the total
time of run i (exact for M0, the density and the autocorrelation; for D it
drops the O(1/N) cross terms of each run's own centring, far below the
interval widths), the plain mean for E[t1] and for brute force. Coverage is the
fraction of runs whose interval contains the reference, with its binomial
standard error; the misses are split into below (the interval lies below the
reference) and above.

Besides the interval the CLI prints ("printed ci"), every interval is also
rebuilt from each run's (value, stderr), so one set of runs compares:
  symmetric  value -+ q se                            (the old interval)
  log        value exp(-+ q se / value)               (normal interval of log D)
  relative   value / (1 +- q se / value)              (make_relative_interval)

Usage (the numbers of docs/validation.md, about 50 minutes on 2 cores):
    scripts/validation/coverage.py --bin build/stickslip --runs 1000 \\
        --excursions 2000,20000 --jobs 2 --out coverage.json > coverage.md
    scripts/validation/coverage.py --load coverage.json --condensed   # the tables of the docs
Raw records go to --out (JSON), the table to stdout (markdown).
"""
import argparse
import concurrent.futures as cf
import json
import math
import subprocess
import sys

Q95 = 1.959963984540054

MODEL = "--friction 1 --noise 1 --dt 1e-2"
ALL = ("diffusivity", "density", "correlation")
CASES = {
    # name: (model flags, commands). Without drag (relaxation inf) U grows like t^(3/2)
    # over an excursion and (U - M0 t)^2 is very heavy-tailed; with drag, like t.
    "white": ("--tau 0 --relaxation inf --bias 0", ALL),
    "coloured": ("--tau 0.1 --relaxation inf --bias 0", ALL),
    "white-bias": ("--tau 0 --relaxation inf --bias 0.3", ALL),
    "coloured-bias": ("--tau 0.1 --relaxation inf --bias 0.3", ALL),
    "white-drag": ("--tau 0 --relaxation 1 --bias 0", ALL),
    "coloured-bias-drag": ("--tau 0.1 --relaxation 1 --bias 0.3", ALL),
    # brute force D_t at the horizon t = 10 (N = trajectories)
    "bruteforce-white": ("--tau 0 --relaxation inf --bias 0 --time 10", ("bruteforce",)),
    "bruteforce-coloured-bias": ("--tau 0.1 --relaxation inf --bias 0.3 --time 10", ("bruteforce",)),
}
DENSITY_FLAGS = "--bins 8 --range -2,2"
DENSITY_BIN = 3  # [-0.5, 0)
CORR_FLAGS = "--lags 2 --max-lag 0.5"
CORR_LAG = 1  # r = 0.25


def run_cli(binary, command, flags, n, seed, model=MODEL):
    size = "--trajectories" if command == "bruteforce" else "--excursions"
    extra = {"density": DENSITY_FLAGS, "correlation": CORR_FLAGS}.get(command, "")
    cmd = [binary, command] + model.split() + flags.split() + extra.split()
    cmd += [size, str(n), "--seed", str(seed), "--threads", "1", "--quiet", "--format", "json"]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def est(e):
    """[value, error, lo, hi] of one JSON estimate; lo, hi None when it prints no interval."""
    ci = e.get("ci")
    if not ci:
        return [e["value"], e["error"], None, None]
    # JSON has no infinity: an unbounded end is printed as null (or "inf")
    lo = -math.inf if ci[0] in (None, "-inf") else ci[0]
    hi = math.inf if ci[1] in (None, "inf") else ci[1]
    return [e["value"], e["error"], lo, hi]


def one_run(binary, case, n, seed, model=MODEL, only=None):
    flags, commands = CASES[case]
    rec = {"case": case, "n": n, "seed": seed}
    for c in commands:
        if only and c not in only:
            continue
        j = run_cli(binary, c, flags, n, seed, model)
        if c == "diffusivity":
            rec["D"] = est(j["diffusivity"])
            if "control_variate" in j:
                rec["pilot"] = j["control_variate"]["pilot_excursions"]
                if "influence" in j["control_variate"]:  # the run's own diagnosis of its interval
                    rec["influence"] = j["control_variate"]["influence"]
            rec["M0"] = est(j["mobility"])
            rec["Et"] = est(j["mean_duration"])
            rec["T"] = n * j["mean_duration"]["value"]
        elif c == "density":
            h = j["histogram"]
            rec["stuck"] = est(j["stuck_probability"])
            b = h["bins"][DENSITY_BIN]
            rec["bin"] = [b["value"], b["error"], None, None]
            rec["h0"] = est(j["variance"])
            rec["Vmean"] = est(j["mean"])
            # density and diffusivity share their excursions bit for bit
            assert "D" not in rec or rec["D"][0] == j["diffusivity"]["value"]
        elif c == "correlation":
            rec["R0"] = est(j["autocorrelation"][0])
            rec["Rlag"] = est(j["autocorrelation"][CORR_LAG])
            rec["hlag"] = est(j["covariance"][CORR_LAG])
        elif c == "bruteforce":
            rec["Dt"] = est(j["diffusivity"])
            rec["M0t"] = est(j["mobility"])
            rec["T"] = float(n)
    return rec


def pooled(records, key):
    """Reference value of `key` over all records of one case."""
    if key == "Et" or key in ("Dt", "M0t"):
        w = [r["n"] for r in records]  # plain means (brute force: equal horizons)
    else:
        w = [r["T"] for r in records]
    if key in ("h0", "hlag"):  # covariance: pooled autocorrelation - pooled mean^2
        rk = "R0" if key == "h0" else "Rlag"
        return pooled(records, rk) - pooled(records, "Vmean") ** 2
    return sum(wi * r[key][0] for wi, r in zip(w, records)) / sum(w)


def interval(kind, v, se, lo, hi):
    if kind == "ci":
        return (lo, hi) if lo is not None else (v - Q95 * se, v + Q95 * se)
    if kind == "sym":
        return v - Q95 * se, v + Q95 * se
    if kind == "log":  # normal interval of log D: D exp(-+ q se / D)
        if v <= 0:
            return (0.0, math.inf) if se > 0 else (v, v)
        h = Q95 * se / v
        return (v * math.exp(-h), v * math.exp(h)) if h < 700 else (0.0, math.inf)
    if kind == "rel":  # relative error, |D_hat/D - 1| <= q se/D_hat (make_relative_interval)
        if v <= 0:
            return (0.0, math.inf) if se > 0 else (v, v)
        h = Q95 * se / v
        return v / (1 + h), (v / (1 - h) if h < 1 else math.inf)
    raise ValueError(kind)


def coverage(records, key, kind, ref):
    lowm = highm = 0
    for r in records:
        lo, hi = interval(kind, *r[key])
        if hi < ref:
            lowm += 1
        elif lo > ref:
            highm += 1
    m = len(records)
    p = 1 - (lowm + highm) / m
    return p, math.sqrt(p * (1 - p) / m), lowm, highm


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="build/stickslip")
    ap.add_argument("--runs", type=int, default=1000)
    ap.add_argument("--excursions", default="2000,20000")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--first-seed", type=int, default=1)
    ap.add_argument("--model", default=MODEL,
                    help=f"the model and engine flags of every run (default '{MODEL}'; e.g. add '--scheme resolvent')")
    ap.add_argument("--commands", default=None, help="only these commands of each case (e.g. 'diffusivity')")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--out", default=None, help="raw records (JSON)")
    ap.add_argument("--load", default=None, help="tabulate these raw records instead of running")
    ap.add_argument("--condensed", action="store_true", help="the tables of docs/validation.md instead of every row")
    a = ap.parse_args()

    if a.load:
        with open(a.load) as f:
            records = json.load(f)
    else:
        # Disjoint seeds for each sample size, so that no run is a prefix of another.
        jobs = [(c, int(n), a.first_seed + 1000000 * j + i) for c in a.cases.split(",")
                for j, n in enumerate(a.excursions.split(",")) for i in range(a.runs)]
        records = []
        with cf.ThreadPoolExecutor(a.jobs) as ex:
            for k, rec in enumerate(ex.map(lambda t: one_run(a.bin, *t, model=a.model, only=a.commands and a.commands.split(",")), jobs)):
                records.append(rec)
                if (k + 1) % 500 == 0:
                    print(f"{k + 1}/{len(jobs)}", file=sys.stderr)
        if a.out:
            with open(a.out, "w") as f:
                json.dump(records, f)

    (condensed if a.condensed else tabulate)(records)


def cell(records, key, kind, ref):
    p, se, lo, hi = coverage(records, key, kind, ref)
    return f"{100 * p:.1f} ± {100 * se:.1f} ({lo}/{hi})"


def condensed(records):
    cases = list(dict.fromkeys(r["case"] for r in records))
    groups = {c: [r for r in records if r["case"] == c] for c in cases}
    sizes = lambda rc: sorted(set(r["n"] for r in rc))
    print("D (D_t for brute force): coverage % ± binomial se (misses below/above); lo < 0: runs whose "
          "symmetric lower bound is negative, which are exactly those whose relative-error upper bound is "
          "infinite.\n")
    print("| case | N | symmetric (old) | log | relative error (new) | lo < 0 |")
    print("|---|---|---|---|---|---|")
    for c, rc in groups.items():
        key = "D" if "D" in rc[0] else "Dt"
        ref = pooled(rc, key)
        for n in sizes(rc):
            rn = [r for r in rc if r["n"] == n]
            neg = sum(1 for r in rn if interval("sym", *r[key])[0] < 0)
            print(f"| {c} | {n} | " + " | ".join(cell(rn, key, k, ref) for k in ("sym", "log", "rel")) +
                  f" | {neg} |")
    # Not inflated: the mean half-width against 1.96 times the spread of D over the runs.
    print("\n| case | N | sd of D / mean se | mean half-width / (1.96 sd of D), bounded intervals |")
    print("|---|---|---|---|")
    for c, rc in groups.items():
        key = "D" if "D" in rc[0] else "Dt"
        for n in sizes(rc):
            rn = [r for r in rc if r["n"] == n]
            v = [r[key][0] for r in rn]
            mean = sum(v) / len(v)
            sd = math.sqrt(sum((x - mean) ** 2 for x in v) / (len(v) - 1))
            se = sum(r[key][1] for r in rn) / len(rn)
            finite = [r for r in rn if r[key][3] is not None and math.isfinite(r[key][3])]
            half = sum(r[key][3] - r[key][2] for r in finite) / (2 * len(finite))
            unbounded = len(rn) - len(finite)
            print(f"| {c} | {n} | {sd / se:.2f} | {half / (Q95 * sd):.2f}" +
                  (f" ({unbounded} unbounded left out)" if unbounded else "") + " |")
    # The printed interval of D must be the relative-error one (make_relative_interval).
    same = differ = 0
    for r in records:
        key = "D" if "D" in r else "Dt"
        lo, hi = interval("rel", *r[key])
        ok = math.isclose(lo, r[key][2], rel_tol=1e-12) and (
            hi == r[key][3] or math.isclose(hi, r[key][3], rel_tol=1e-12))
        same, differ = same + ok, differ + (not ok)
    print(f"\nPrinted interval of D (D_t) = relative-error formula in {same} runs, different in {differ}.")
    keys = [k for k in ("M0", "Et", "stuck", "bin", "h0", "hlag") if any(k in r for r in records)]
    print("\nThe other quantities, with the symmetric interval they print (h(0): relative error in brackets).\n")
    print("| case | N | " + " | ".join(NAMES[k] for k in keys) + " |")
    print("|---|---|" + "---|" * len(keys))
    for c, rc in groups.items():
        if "M0" not in rc[0]:
            continue
        refs = {k: pooled(rc, k) for k in keys}
        for n in sizes(rc):
            rn = [r for r in rc if r["n"] == n]
            cells = []
            for k in keys:
                t = cell(rn, k, "sym", refs[k])
                if k == "h0":
                    p, _, lo, hi = coverage(rn, k, "rel", refs[k])
                    t += f" [{100 * p:.1f} ({lo}/{hi})]"
                cells.append(t)
            print(f"| {c} | {n} | " + " | ".join(cells) + " |")


POSITIVE = {"D", "Et", "stuck", "bin", "h0", "R0", "Dt"}  # where log and rel apply
NAMES = {"D": "D", "M0": "M0", "Et": "E[t1]", "stuck": "P(stuck)", "bin": "p(v), v in [-0.5,0)",
         "h0": "h(0) = var V", "Rlag": "E[V(s)V(s+0.25)]", "hlag": "h(0.25)", "Dt": "D_t (t = 10)",
         "M0t": "M0_t (t = 10)"}


def tabulate(records):
    keys = ["D", "M0", "Et", "stuck", "bin", "h0", "Rlag", "hlag", "Dt", "M0t"]
    print("Coverage % +- binomial se (misses below / above the reference); lo<0: runs whose lower bound is "
          "negative (symmetric / printed ci), for the positive quantities.\n")
    print("| case | N | runs | quantity | reference | symmetric | log | relative | printed ci | lo<0 |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    cases = list(dict.fromkeys(r["case"] for r in records))
    for case in cases:
        rc = [r for r in records if r["case"] == case]
        for key in keys:
            if key not in rc[0]:
                continue
            if key == "stuck" and all(r[key][0] == 0 for r in rc):
                continue
            ref = pooled(rc, key)
            for n in sorted(set(r["n"] for r in rc)):
                rn = [r for r in rc if r["n"] == n]
                cells = []
                for kind in ("sym", "log", "rel", "ci"):
                    if (kind in ("log", "rel") and key not in POSITIVE) or (kind == "ci" and rn[0][key][2] is None):
                        cells.append("")
                        continue
                    p, se, lo, hi = coverage(rn, key, kind, ref)
                    cells.append(f"{100 * p:.1f} +- {100 * se:.1f} ({lo}/{hi})")
                if key in POSITIVE:
                    neg = [sum(1 for r in rn if interval(k, *r[key])[0] < 0) for k in ("sym", "ci")]
                    negs = f"{neg[0]}/{neg[1]}" if rn[0][key][2] is not None else f"{neg[0]}"
                else:
                    negs = ""
                print(f"| {case} | {n} | {len(rn)} | {NAMES[key]} | {ref:.5g} | " + " | ".join(cells) + f" | {negs} |")


if __name__ == "__main__":
    main()
