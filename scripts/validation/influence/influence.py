#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Why D's 95% interval under-covers without drag: the diagnosis of
docs/validation.md ("Why D's interval under-covers without drag").

Reads the files of excursion_dump (one record (U, t, M, C, capped) per long
excursion, in index order) and prints, per file:

1. the influence functions' shape over the whole file: skewness, excess
   kurtosis (and its spread over 10 disjoint parts: a fourth moment that the
   data pin down gives parts that agree), the Hill estimate of the tail index
   of |psi| from its k = 100, 300, 1000 largest terms, and Owen's O(1/n)
   coverage error of a two-sided 95% t interval, (0.14 kappa - 2.12 gamma^2)/n;
2. coverage of the control-variate interval D_cv -+ 1.96 se over disjoint runs
   of n excursions, with beta (the coefficient of C) fitted on the run itself
   (what stickslip does), fixed at the file's pooled value, fixed at 1, fitted
   on the other half of the run (2-fold cross-fitting), or fitted on an
   independent pilot of P excursions (the P before the run).

The reference is the pooled D_cv of the file. Formulas: control_variate.hpp.
Usage: influence.py FILE... [--n 2000]   (/usr/bin/python3: numpy)
"""
import argparse

import numpy as np

Q = 1.959964


def load(path):
    a = np.fromfile(path).reshape(-1, 5)
    a = a[a[:, 4] == 0]  # capped excursions are dropped, as by the run
    return tuple(a[:, k] for k in range(4))


def centred(U, t):
    tbar = t.mean()
    w = U - U.sum() / t.sum() * t
    D = np.sum(w**2) / t.sum()
    c = np.mean(w * t) / tbar
    return tbar, w, c, w**2 - D * t - 2 * c * w  # phi: the plain D's influence, times tbar


def fitted_beta(U, t, M, C):
    return np.mean(centred(U, t)[3] * C) / np.mean(C**2)


def with_beta(U, t, M, C, beta):
    """D_cv, its standard error and its influence psi (over tbar) for a given beta (a number or one per excursion)."""
    tbar, w, c, _ = centred(U, t)
    D = (np.sum(w**2) - np.sum(beta * C)) / t.sum()
    psi = w**2 - beta * C - D * t - 2 * c * w
    return D, np.sqrt(np.mean(psi**2) / (len(U) - 1)) / tbar, psi / tbar


def shape(x):
    x = x - x.mean()
    s2 = np.mean(x**2)
    return np.mean(x**3) / s2**1.5, np.mean(x**4) / s2**2 - 3


def hill(x, k):
    a = np.sort(np.abs(x))[::-1][: k + 1]
    return 1.0 / np.mean(np.log(a[:k] / a[k]))


def diagnostics(data, n):
    U, t, M, C = data
    beta = fitted_beta(*data)
    _, _, psi = with_beta(*data, beta)
    tbar, w, c, phi = centred(U, t)
    bm = np.mean(w * M) / np.mean(M**2)
    psim = U - bm * M - (U.sum() - bm * M.sum()) / t.sum() * t
    print(f"  pooled: N = {len(U)}, D_cv = {with_beta(*data, beta)[0]:.5g}, beta = {beta:.3f}")
    print("  | influence of | skewness | excess kurtosis (10 parts) | Hill alpha, k = 100/300/1000 | Owen, n = %d |" % n)
    print("  |---|---|---|---|---|")
    for name, x in (("D plain", phi), ("D_cv", psi), ("M0_cv", psim), ("t", t - tbar)):
        g, k = shape(x)
        parts = [shape(p)[1] for p in np.array_split(x, 10)]
        h = [hill(x, kk) for kk in (100, 300, 1000)]
        print(f"  | {name} | {g:.1f} | {k:.3g} ({min(parts):.3g}..{max(parts):.3g}) | "
              f"{h[0]:.1f} / {h[1]:.1f} / {h[2]:.1f} | {100 * (0.14 * k - 2.12 * g * g) / n:+.0f}% |")


def coverage(data, n, pilots=(2000, 8000, 32000)):
    U, t, M, C = data
    pooled = fitted_beta(*data)
    ref = with_beta(*data, pooled)[0]
    runs = len(U) // n
    first = int(np.ceil(max(pilots) / n))  # every variant on the same runs (those with a full pilot before them)
    rules = {"fitted on the run": lambda x, r: fitted_beta(*x),
             "pooled (oracle)": lambda x, r: pooled,
             "1": lambda x, r: 1.0}

    def crossfit(x, r):
        half = (np.arange(n) // 64) % 2 == 0
        a = fitted_beta(*(y[half] for y in x))
        b = fitted_beta(*(y[~half] for y in x))
        return np.where(half, b, a)
    rules["2-fold cross-fitted"] = crossfit
    for P in pilots:
        rules[f"pilot of {P}"] = lambda x, r, P=P: fitted_beta(*(y[r * n - P:r * n] for y in data))
    print(f"  {runs - first} runs of {n}; reference: the pooled D_cv")
    print("  | beta | covers (below/above) | sd of D / mean se |")
    print("  |---|---|---|")
    for name, rule in rules.items():
        out = []
        for r in range(first, runs):
            x = tuple(y[r * n:(r + 1) * n] for y in data)
            out.append(with_beta(*x, rule(x, r))[:2])
        D, se = np.array(out).T
        lo, hi = D - Q * se, D + Q * se
        cov = np.mean((lo <= ref) & (ref <= hi))
        print(f"  | {name} | {100 * cov:.1f}% ({np.sum(hi < ref)}/{np.sum(lo > ref)}) | {np.std(D) / np.mean(se):.2f} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+")
    ap.add_argument("--n", type=int, default=2000, help="excursions per run")
    args = ap.parse_args()
    for path in args.files:
        print(path)
        data = load(path)
        diagnostics(data, args.n)
        coverage(data, args.n)


if __name__ == "__main__":
    main()
