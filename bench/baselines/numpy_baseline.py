#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""NumPy baseline: the Fig. 2 case, vectorised across excursions in flight.

The way users write this computation today in Python. Inclusion scheme of
docs/theory.md section 5 (exact OU pair step, soft threshold, left-point U) with the
long excursions of section 6: rule Q stop test (while stuck at the start of the
step, the excursion half ends if X's endpoint is beyond the opposite threshold
or, both ends inside, with the Brownian-bridge probability
exp(-(X_n - x)(X_{n+1} - x) tau^2 / h)); the detecting step is not applied and
the next half restarts exactly at its threshold.

K lanes (--lanes) each run one long excursion at a time; a lane that finishes
starts the next excursion until --excursions have been started; finished lanes
are then dropped. Prints JSON {"D", "stderr", "steps", "seconds", ...}:
D = sum (U - M0 t)^2 / sum t and its delta-method standard error (section 6).
"""
import argparse
import json
import sys
import time

try:
    import numpy as np
except ImportError:
    sys.stderr.write("numpy_baseline.py: numpy is not installed for %s\n" % sys.executable)
    sys.exit(4)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--excursions", type=int, default=2000)
    ap.add_argument("--dt", type=float, default=1e-3)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--lanes", type=int, default=1024, help="excursions in flight (vector width)")
    args = ap.parse_args()
    n_exc, h = args.excursions, args.dt
    if n_exc < 2 or not h > 0:
        ap.error("need --excursions >= 2 and --dt > 0")

    # Fig. 2 case (SI units) and the per-run constants.
    friction, noise, tau, relax, bias = 3.84, 5.0, 0.5, 0.067, 0.342
    a = np.sqrt(noise / 2)
    x_up, x_down = (friction - bias) / a, (-friction - bias) / a
    r = h / tau
    e1, e2 = np.exp(-r), np.exp(-2 * r)
    m1, m2 = tau / h * (1 - e1), e1
    s11 = tau / h**2 * (2 * r - 3 + 4 * e1 - e2)
    s12 = (1 - e1) ** 2 / h
    s22 = (1 - e2) / tau
    l11 = np.sqrt(s11)
    l21 = s12 / l11
    l22 = np.sqrt(s22 - l21 * l21)
    band, bridge_rate = h * friction, tau * tau / h

    rng = np.random.default_rng(args.seed)
    k = min(args.lanes, n_exc)
    x = np.full(k, x_up)
    v = np.zeros(k)
    up = np.ones(k, dtype=bool)  # True: +HLE (target x_down), False: -HLE (target x_up)
    vsum = np.zeros(k)
    steps = np.zeros(k, dtype=np.int64)
    started = k
    U, T = [], []
    total_steps = 0

    t0 = time.perf_counter()
    while x.size:
        n = x.size
        z1 = rng.standard_normal(n)
        z2 = rng.standard_normal(n)
        xbar = m1 * x + l11 * z1
        xn = m2 * x + l21 * z1 + l22 * z2
        f = v + h * (-v / relax + bias + a * xbar)
        target = np.where(up, x_down, x_up)
        stuck = (v == 0.0) & (x >= x_down) & (x <= x_up)
        crossed = stuck & np.where(up, xn <= target, xn >= target)
        cand = np.flatnonzero(stuck & ~crossed)
        if cand.size:
            e = (x[cand] - target[cand]) * (xn[cand] - target[cand]) * bridge_rate
            u = rng.random(cand.size)
            crossed[cand] = (e < 50.0) & (u < np.exp(-np.minimum(e, 50.0)))
        go = ~crossed
        vn = f - np.clip(f, -band, band)
        vsum += np.where(go, v, 0.0)  # left-point rule
        steps += go
        x = np.where(go, xn, x)
        v = np.where(go, vn, v)
        if not crossed.any():
            continue
        ended = np.flatnonzero(crossed)
        plus = ended[up[ended]]
        minus = ended[~up[ended]]
        # +HLE finished: start the -HLE at (x-*, 0).
        up[plus] = False
        x[plus] = x_down
        v[plus] = 0.0
        if minus.size:
            # Long excursion finished: record, then restart or retire the lane.
            U.append(h * vsum[minus])
            T.append(h * steps[minus].astype(np.float64))
            total_steps += int(steps[minus].sum())
            n_new = min(minus.size, n_exc - started)
            restart, retire = minus[:n_new], minus[n_new:]
            started += n_new
            up[restart] = True
            x[restart] = x_up
            v[restart] = 0.0
            vsum[restart] = 0.0
            steps[restart] = 0
            if retire.size:
                keep = np.ones(n, dtype=bool)
                keep[retire] = False
                x, v, up, vsum, steps = x[keep], v[keep], up[keep], vsum[keep], steps[keep]
    seconds = time.perf_counter() - t0

    U = np.concatenate(U)
    T = np.concatenate(T)
    m0 = U.sum() / T.sum()
    res = U - m0 * T
    D = (res**2).sum() / T.sum()
    et = T.mean()
    c = (res * T).mean() / et
    phi = (res**2 - D * T - 2 * c * res) / et
    se = phi.std(ddof=1) / np.sqrt(U.size)
    print(json.dumps({"D": float(D), "stderr": float(se), "M0": float(m0), "steps": total_steps,
                      "seconds": seconds, "excursions": int(U.size), "dt": h, "seed": args.seed,
                      "lanes": k, "numpy": np.__version__}))


if __name__ == "__main__":
    main()
