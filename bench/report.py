#!/usr/bin/python3
"""Prints bench/run.sh's table from the JSON files it left in a directory.

Standard library only. Exit status 1 when a baseline's D disagrees with
stickslip's by more than 4 combined standard errors, else 0.
"""
import argparse
import json
import math
import os
import sys

AGREE_SIGMAS = 4.0


def load(path):
    with open(path) as f:
        return json.load(f)


def fmt_rate(x):
    if x is None:
        return "-"
    for unit, scale in (("G", 1e9), ("M", 1e6), ("k", 1e3)):
        if x >= scale:
            return "%.2f%s" % (x / scale, unit)
    return "%.0f" % x


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--excursions", type=int)
    ap.add_argument("--numpy-excursions", type=int)
    ap.add_argument("--dt")
    ap.add_argument("--cores")
    a = ap.parse_args()
    d = a.dir

    kj = load(os.path.join(d, "kernels.json"))
    bm = {b["name"]: b for b in kj["benchmarks"] if b.get("run_type", "iteration") == "iteration"}

    def kernel(name):
        b = bm[name]
        per = b.get("steps_per_excursion", b.get("events_per_excursion"))
        return b["items_per_second"], per

    ss = load(os.path.join(d, "stickslip.json"))
    ss_steps = ss["work"]["steps"]
    ss_sec = ss["work"]["seconds"]
    ss_rate = ss_steps / ss_sec
    ss_D, ss_se = ss["diffusivity"]["value"], ss["diffusivity"]["stderr"]

    philox_rate, _ = kernel("BM_PhiloxNormalPairs")
    inc_fig2, inc_fig2_per = kernel("BM_InclusionSteps/fig2_dt1e-4")
    inc_dry, inc_dry_per = kernel("BM_InclusionSteps/dry_dt1e-3")
    pd_fig2, pd_fig2_per = kernel("BM_PdmpEvents/fig2_grid0.125")
    pd_dry, pd_dry_per = kernel("BM_PdmpEvents/dry_grid0.125")

    ctx = kj.get("context", {})
    print()
    print("stickslip benchmarks -- host %s, %s cores at %s MHz; every rate is ONE core (single thread)"
          % (ctx.get("host_name", "?"), a.cores, ctx.get("mhz_per_cpu", "?")))
    if ctx.get("library_build_type") == "debug":
        print("(Google Benchmark's own library reports a debug build, as Debian ships it; that does not"
              " affect the timed code, which is stickslip's Release build)")
    print()
    print("A. Kernels (Google Benchmark, single thread). ratio = rate / inclusion kernel, same case")
    hdr = "  %-44s %13s %8s %12s %10s" % ("kernel", "items/s", "ratio", "items/exc", "exc/s")
    print(hdr)
    print("  " + "-" * (len(hdr) - 2))
    rows = [
        ("Philox normal2 pairs alone (RNG cost)", philox_rate, philox_rate / inc_fig2, None),
        ("inclusion steps, Fig. 2, dt 1e-4", inc_fig2, 1.0, inc_fig2_per),
        ("inclusion steps, pure dry, dt 1e-3", inc_dry, 1.0, inc_dry_per),
        ("PDMP events, Fig. 2, grid 0.125", pd_fig2, None, pd_fig2_per),
        ("PDMP events, pure dry, grid 0.125", pd_dry, None, pd_dry_per),
    ]
    for name, rate, ratio, per in rows:
        print("  %-44s %13s %8s %12s %10s" % (
            name, fmt_rate(rate), "-" if ratio is None else "%.2f" % ratio,
            "-" if per is None else "%.0f" % per, "-" if per is None else fmt_rate(rate / per)))
    print("  (one inclusion step draws one normal pair: a Philox rate close to the step rate means the")
    print("   random numbers are nearly the whole cost of a step, the practical limit on this core;")
    print("   PDMP: one event = two uniforms; exc/s compares the engines per long excursion)")
    print()

    print("B. Whole runs, Fig. 2 case, dt %s s, one thread. ratio = steps/s / stickslip's." % a.dt)
    print("   Agreement: |D - D_stickslip| <= %g sqrt(SE^2 + SE_stickslip^2)" % AGREE_SIGMAS)
    hdr = "  %-40s %7s %10s %9s %7s %24s %14s" % ("engine / baseline", "N", "steps/s", "seconds", "ratio",
                                                 "D +- SE [m^2/s]", "agrees (4 sd)")
    print(hdr)
    print("  " + "-" * (len(hdr) - 2))
    print("  %-40s %7d %10s %9.2f %7s %24s %14s" % (
        "stickslip diffusivity --threads 1", a.excursions, fmt_rate(ss_rate), ss_sec, "1.00",
        "%.4e +- %.2e" % (ss_D, ss_se), "(ref)"))
    print("  %-40s %7s %10s %9.2f %7.2f %24s %14s" % (
        "RNG alone: Philox pairs, same steps", "", fmt_rate(philox_rate), ss_steps / philox_rate,
        philox_rate / ss_rate, "-", "-"))
    print("  (the RNG row: seconds that stickslip's step count costs in random numbers alone)")
    failed = False
    baselines = [
        ("plain C++ mt19937_64, -O3 -march=native", "plain_O3", a.excursions),
        ("plain C++ mt19937_64, -O2", "plain_O2", a.excursions),
        ("NumPy, vectorised over excursions", "numpy", a.numpy_excursions),
    ]
    for name, key, n in baselines:
        path = os.path.join(d, key + ".json")
        if not os.path.exists(path):
            why = "not run"
            skip = os.path.join(d, key + ".skip")
            if os.path.exists(skip):
                with open(skip) as f:
                    why = f.read().strip()
            print("  %-40s %7d  %s" % (name, n, why))
            continue
        r = load(path)
        rate = r["steps"] / r["seconds"]
        diff = abs(r["D"] - ss_D)
        tol = AGREE_SIGMAS * math.hypot(r["stderr"], ss_se)
        ok = diff <= tol
        failed |= not ok
        print("  %-40s %7d %10s %9.2f %7.2f %24s %14s" % (
            name, n, fmt_rate(rate), r["seconds"], rate / ss_rate, "%.4e +- %.2e" % (r["D"], r["stderr"]),
            "%s (%.1f sd)" % ("PASS" if ok else "FAIL", diff / (tol / AGREE_SIGMAS))))
    print()
    print("overall: %s" % ("FAIL" if failed else "PASS"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
