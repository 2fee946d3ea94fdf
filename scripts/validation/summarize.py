#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Prints the markdown tables of docs/validation.md from the JSON files written
by convergence.sh (one `stickslip --format json` result per file)."""
import json
import math
import os
import sys

out = sys.argv[1] if len(sys.argv) > 1 else "build/validation"


def load(name):
    path = os.path.join(out, name + ".json")
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def fmt(x, se):
    return f"{x:.4g} ± {se:.2g}"


def row_le(label, j, ref=None, ref_label=""):
    d, m, t = j["diffusivity"], j["mobility"], j["mean_duration"]
    cells = [label, fmt(d["value"], d["error"]), fmt(m["value"], m["error"]), fmt(t["value"], t["error"]),
             f"{j['completed']}", j["stop_rule"]]
    if ref is not None:
        z = (d["value"] - ref) / d["error"]
        cells += [f"{100 * (d['value'] / ref - 1):+.2f}%", f"{z:+.2f}"]
    return "| " + " | ".join(cells) + " |"


print("### Fig. 2/4 case: D against the discretisation\n")
print("| run | D [m^2/s] | M0 [m/s] | E[t1] [s] | N | stop rule |")
print("|---|---|---|---|---|---|")
for dt in ("1e-3", "3e-4", "1e-4"):
    j = load(f"incl_{dt}")
    if j: print(row_le(f"inclusion dt = {dt} s", j))
for g in ("0.25", "0.125", "0.0625"):
    j = load(f"pdmp_{g}")
    if j: print(row_le(f"pdmp grid = {g} s^-1/2", j))

print("\n### White noise (tau = 0), nondimensional, against the exact quadrature\n")
print("| run | D' | M0' | cycle time | N | rule | D' vs exact | z |")
print("|---|---|---|---|---|---|---|---|")
for name, label, ref in [("white_dry_1e-2", "dry, dt' = 1e-2, seed 1", 1.25),
                         ("wd_1e-2_s2", "dry, dt' = 1e-2, seed 2", 1.25),
                         ("wd_1e-2_s3", "dry, dt' = 1e-2, seed 3", 1.25),
                         ("white_dry_3e-3", "dry, dt' = 3e-3, seed 1", 1.25),
                         ("white_dry_1e-3", "dry, dt' = 1e-3, seed 1", 1.25),
                         ("wd_1e-3_s4", "dry, dt' = 1e-3, seed 4", 1.25),
                         ("white_rb_1e-2", "relaxation' 0.2, bias' 0.3, dt' = 1e-2", 0.0156139680264),
                         ("white_rb_3e-3", "relaxation' 0.2, bias' 0.3, dt' = 3e-3", 0.0156139680264),
                         ("white_rb_1e-3", "relaxation' 0.2, bias' 0.3, dt' = 1e-3", 0.0156139680264),
                         ("tiny_tau_1e-3", "colored tau' = 1e-4, dt' = 1e-3", 1.25)]:
    j = load(name)
    if j: print(row_le(label, j, ref))

print("\n### Brute force (PDMP) against long excursions\n")
print("| case | estimator | D [m^2/s] | N |")
print("|---|---|---|---|")
for case, le_name in [("fig2", "pdmp_0.125"), ("drv", "le_drv_renewal")]:
    for t in ("10", "20"):
        j = load(f"bf_{case}_{t}")
        if j:
            d = j["diffusivity"]
            print(f"| {case} | brute force t = {t} s | {fmt(d['value'], d['error'])} | {j['params']['trajectories']} |")
    a, b = load(f"bf_{case}_10"), load(f"bf_{case}_20")
    if a and b:
        da, db = a["diffusivity"], b["diffusivity"]
        ext = 2 * db["value"] - da["value"]
        se = math.hypot(2 * db["error"], da["error"])
        print(f"| {case} | brute force extrapolated in 1/t | {fmt(ext, se)} | |")
    for nm in ([le_name] if case == "fig2" else ["le_drv_renewal", "le_drv_paper"]):
        j = load(nm)
        if j:
            d = j["diffusivity"]
            print(f"| {case} | long excursions, {j['estimator']} | {fmt(d['value'], d['error'])} | {j['completed']} |")
