#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Regenerates the paper's Table I and Figs. 2 to 9 from the `stickslip` CLI.

Run through the wrapper `bash scripts/figures [--quick] [--out DIR] [--only fig4,fig9]
[--threads N]`. Every number comes from a `stickslip <sub> --format json --quiet` call:
the simulations and the closed forms alike (`stickslip analytic`); this script only
plots, tabulates and compares (z-scores, least-squares slopes of the plotted points).

Outputs (in --out, default docs/figures, or build/figures-quick with --quick):
table1.md, table1.png, fig2.png ... fig9.png and summary.json (the numbers the docs
quote, with the timing of each figure).
"""
import argparse
import datetime
import hashlib
import json
import math
import os
import shlex
import subprocess
import sys
import time

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Model arguments -------------------------------------------------------------------
# Pure dry friction, nondimensional (time unit noise/friction^2 = 1).
ND = ["--friction", "1", "--noise", "1", "--relaxation", "inf", "--bias", "0"]
DELTA = 3.84
TAUL = 0.067
GBAR = 0.342
# The paper's b(v) = -v/tauL + gbar with Delta = 3.84 (noise and tau given per call).
PAPER_B = ["--friction", str(DELTA), "--relaxation", str(TAUL), "--bias", str(GBAR)]
ZERO_B = ["--friction", str(DELTA), "--relaxation", "inf", "--bias", "0"]
# How the plots name the drift of PAPER_B.
B_TEXT = "b(v) = -v/tauL + gbar, tauL = 0.067 s, gbar = 0.342 m/s$^2$"
# The inclusion engine's scheme at its defaults (--scheme auto): event for the
# affine law, resolvent for any other (the event scheme takes the affine law only).
INCLUSION_SCHEME = "event"
# summary.json's name for the paper's law.
PAPER_DRIFT = "-v/tauL + gbar (the paper's)"
# The figures built on the paper's b(v): `--drift` replaces it in these; the
# others are pure dry friction (b = 0), where a law does not enter.
DRIFT_FIGURES = ["fig2", "fig3", "fig4", "fig5", "fig6", "fig9"]


def use_drift_law(expr, params=""):
    """Every figure built on the paper's b(v) runs the law `expr` (stickslip's
    --drift, with --drift-params `params`) instead, Delta kept."""
    global PAPER_B, B_TEXT, INCLUSION_SCHEME
    INCLUSION_SCHEME = "resolvent"
    PAPER_B = ["--friction", str(DELTA), "--drift", expr] + (["--drift-params", params] if params else [])
    B_TEXT = f"b(v) = {expr}" + (f" ({params})" if params else "")

def use_static_friction(ratio):
    """Every figure runs with a static friction `ratio` times its friction
    (stickslip's --static-friction): a stuck object starts only when the force
    exceeds it. White-noise curves do not change (a white force holds the
    object at rest for no positive time: stickslip's note says so)."""
    global ND, PAPER_B, ZERO_B, B_TEXT
    ND = ND + ["--static-friction", repr(float(ratio))]  # ND's friction is 1
    PAPER_B = PAPER_B + ["--static-friction", repr(ratio * DELTA)]
    ZERO_B = ZERO_B + ["--static-friction", repr(ratio * DELTA)]
    B_TEXT = f"{B_TEXT}, static friction {ratio:g} Delta"


TABLE1_TIMES = [0.05, 0.125, 0.25, 0.5, 1.0, 2.5]
TABLE1_PAPER_MC = [0.950, 0.876, 0.757, 0.569, 0.337, 0.091]
TABLE1_PAPER_EF = [0.950, 0.875, 0.757, 0.568, 0.336, 0.090]

FIGURES = ["table1", "fig2", "fig3", "fig4", "fig5", "fig6", "fig7", "fig8", "fig9"]

# Run sizes -------------------------------------------------------------------------
# The default sizes were chosen from measured costs on 2 cores (inclusion engine
# ~2.5e7 steps/s, PDMP ~3.5e7 events/s before its exponential ziggurat, about
# 1.5 times that since); see docs/validation.md, last section.
DEFAULT = {
    "table1": {"tau": 5e-6, "dt": 2.5e-3, "trajectories": 500000},
    "fig23": {"excursions_pdmp": 4000, "excursions_incl": 1000, "max_index": 200},
    "fig4": {
        "grid": 0.125,
        "kolmogorov_precision": 0.01,
        # tau: (Gammas, N pdmp, N inclusion). The low-noise end is cut where
        # E[t1] explodes (tau = 0.5: E[t1] ~ 3000 s at Gamma = 1; tau = 1: ~1000 s
        # at Gamma = 2.5, ~5000 s at Gamma = 2).
        "taus": {
            0.125: ([1, 1.5, 2, 3, 4, 5, 7, 10], 10000, 4000),
            0.25: ([1, 1.5, 2, 3, 4, 5, 7, 10], 10000, 4000),
            0.5: ([1.5, 2, 3, 4, 5, 7, 10], 10000, 2000),
            1.0: ([3, 4, 5, 7, 10], 10000, 1500),
        },
    },
    "fig5": {
        "noise": 5.0, "max_lag": 1.5, "lags": 60, "grid": 0.125, "sample_dt": 2.5e-3,
        # tau: (N pdmp, N inclusion). The inclusion engine runs its defaults (the
        # event scheme at dt auto), its path sampled on the PDMP's grid sample_dt
        "taus": {0.25: (20000, 12000), 0.5: (16000, 8000), 1.0: (8000, 3000)},
    },
    "fig6": {"tau": 1e-5, "noise": 0.16, "dt": 1e-5, "excursions": 8000,
             "range": (-0.12, 0.12), "bins": 96, "paths": 10, "path_time": 2.0, "path_dt": 1e-5},
    "fig7": {"taus": [5e-2, 5e-3, 5e-4, 5e-5], "dt": 1e-3, "trajectories": 100000,
             "times": [0.25, 0.5, 1.0, 2.0], "range": (-3.0, 4.0), "bins": 70},
    "fig8": {"dt": 1e-3, "max_lag": 5.0, "lags": 50,
             # tau': N excursions (equalises roughly the total simulated time)
             "taus": {5e-5: 2000, 5e-4: 2500, 5e-3: 5000, 5e-2: 50000}},
    "fig9": {
        "dt": 1e-4, "bf_time": 10.0, "bf_trajectories": 1000,
        "gammas": [1.0, 1.778, 3.162, 5.623, 10.0], "bf_gammas": [1.0, 3.162, 10.0],
        # tau: N excursions per point for (b = 0, paper's b). Small tau: E[t1] ~ 100 s
        # at Gamma = 10 (1e6 steps per excursion); tau >= 1e-3 s: cheap excursions but
        # very heavy-tailed displacements (tau' ~ 0.01 - 0.1), so many more of them.
        "taus": {1e-5: (1000, 1000), 1e-4: (1200, 1500), 1e-3: (20000, 10000), 1e-2: (30000, 20000)},
        "white_points": 19,
    },
}

QUICK = {
    "table1": {"tau": 5e-6, "dt": 1.25e-2, "trajectories": 50000},
    "fig23": {"excursions_pdmp": 200, "excursions_incl": 50, "max_index": 40},
    "fig4": {
        "grid": 0.125,
        "kolmogorov_precision": 0.05,
        "taus": {0.125: ([2, 5, 10], 400, 200), 0.25: ([2, 5, 10], 400, 200),
                 0.5: ([3, 5, 10], 300, 100), 1.0: ([5, 10], 200, 60)},
    },
    "fig5": {"noise": 5.0, "max_lag": 1.5, "lags": 30, "grid": 0.125, "sample_dt": 5e-3,
             "taus": {0.25: (300, 200), 0.5: (200, 100), 1.0: (100, 50)}},
    "fig6": {"tau": 1e-5, "noise": 0.16, "dt": 1e-4, "excursions": 1000,
             "range": (-0.12, 0.12), "bins": 48, "paths": 10, "path_time": 2.0, "path_dt": 1e-4},
    "fig7": {"taus": [5e-2, 5e-3, 5e-4, 5e-5], "dt": 5e-3, "trajectories": 20000,
             "times": [0.25, 0.5, 1.0, 2.0], "range": (-3.0, 4.0), "bins": 35},
    "fig8": {"dt": 5e-3, "max_lag": 5.0, "lags": 25, "taus": {5e-5: 120, 5e-4: 160, 5e-3: 300, 5e-2: 3000}},
    "fig9": {"dt": 1e-3, "bf_time": 10.0, "bf_trajectories": 100, "kolmogorov_precision": 0.05,
             "gammas": [1.0, 3.162, 10.0], "bf_gammas": [1.0, 10.0],
             "taus": {1e-5: (40, 40), 1e-4: (40, 40), 1e-3: (300, 200), 1e-2: (400, 300)}, "white_points": 7},
}


# Running stickslip -------------------------------------------------------------------
class StickslipFailure(RuntimeError):
    def __init__(self, message, exit_code=None):
        super().__init__(message)
        self.exit_code = exit_code


def fmt(x):
    """Number as a CLI argument (shortest round-trip form)."""
    if isinstance(x, str):
        return x
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    return repr(float(x))


class Runner:
    def __init__(self, binary, threads, cache_dir=None, verbose=True):
        self.binary = binary
        self.threads = threads
        self.cache_dir = cache_dir
        self.verbose = verbose
        self.calls = 0
        self.warnings = {}

    def __call__(self, sub, args, seed=None, threads=True, label=None, fig=None):
        cmd = [self.binary, sub] + [fmt(a) for a in args] + ["--format", "json", "--quiet"]
        if seed is not None:
            cmd += ["--seed", str(seed)]
        key_cmd = cmd[1:]  # results do not depend on the thread count
        if threads:
            cmd += ["--threads", str(self.threads)]
        cache_file = None
        if self.cache_dir:
            h = hashlib.sha1(json.dumps(key_cmd).encode()).hexdigest()[:20]
            cache_file = os.path.join(self.cache_dir, f"{sub}-{h}.json")
            if os.path.exists(cache_file):
                with open(cache_file) as f:
                    return json.load(f)
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        dt = time.perf_counter() - t0
        self.calls += 1
        if proc.returncode != 0:
            raise StickslipFailure(
                f"stickslip call failed (exit code {proc.returncode}):\n  {shlex.join(cmd)}\n"
                f"--- its stderr ---\n{proc.stderr.strip()}\n------------------", proc.returncode)
        try:
            data = json.loads(proc.stdout)
        except json.JSONDecodeError as e:
            raise StickslipFailure(f"stickslip printed no valid JSON ({e}):\n  {shlex.join(cmd)}\n"
                                   f"--- its stderr ---\n{proc.stderr.strip()}") from e
        if self.verbose:
            print(f"    {label or sub}: {dt:.1f} s", file=sys.stderr, flush=True)
        for w in data.get("warnings", []) if isinstance(data, dict) else []:
            self.warnings.setdefault(fig or "?", set()).add(w)
        if cache_file:
            os.makedirs(self.cache_dir, exist_ok=True)
            with open(cache_file, "w") as f:
                json.dump(data, f)
        return data


# Helpers ---------------------------------------------------------------------------
def est(d):
    """(value, error) of an estimate object (the report's "error": a standard
    error when sampled, 0 when exact; 0 where a solver has none)."""
    return float(d["value"]), float(d.get("error") or 0.0)


def values(series):
    """The values of a series of estimates (a list of {time|lag, value, ...})."""
    return np.array([p["value"] for p in series], float)


def rnd(x, n=4):
    """Rounded float for summary.json (significant digits)."""
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return None
    return float(f"{x:.{n}g}")


def zscores(a, sa, b, sb=0.0):
    a, sa, b, sb = map(np.asarray, (a, sa, b, sb))
    se = np.sqrt(sa ** 2 + sb ** 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(se > 0, (a - b) / se, np.nan)
    return z


def zsummary(z):
    z = np.asarray(z, float)
    z = z[np.isfinite(z)]
    if z.size == 0:
        return {"n": 0}
    return {"n": int(z.size), "max_abs_z": rnd(float(np.max(np.abs(z))), 3),
            "chi2_per_n": rnd(float(np.mean(z ** 2)), 3), "mean_z": rnd(float(np.mean(z)), 3)}


def even_grid(lo, hi, n):
    """`lo:hi:n` (n evenly spaced values, inclusive) for --velocities."""
    return f"{lo!r}:{hi!r}:{n}"


def bin_average(runner, model_args, lo, hi, nbins, k=8, extra=(), key="stationary_density", fig=None):
    """Closed-form density averaged over each of nbins equal bins of [lo, hi]
    (midpoint rule with k sub-points per bin), from `stickslip analytic`."""
    h = (hi - lo) / (nbins * k)
    a = runner("analytic", model_args + [f"--velocities={even_grid(lo + h / 2, hi - h / 2, nbins * k)}"]
               + list(extra), threads=False, label="analytic (bin averages)", fig=fig)
    vals = np.asarray(a[key], float)
    return a, vals.reshape(vals.shape[:-1] + (nbins, k)).mean(axis=-1)


def savefig(fig, path, written):
    fig.savefig(path, dpi=130)
    plt.close(fig)
    written.append(path)


TAU_COLORS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple"]


# Table I -----------------------------------------------------------------------------
def make_table1(R, cfg, out, written, summary, seed):
    c = cfg["table1"]
    times = ",".join(fmt(t) for t in TABLE1_TIMES)
    mc = R("moments", ND + ["--tau", c["tau"], "--scheme", "resolvent", "--dt", c["dt"], "--v0", 1, "--times", times,
                            "--trajectories", c["trajectories"]], seed=seed, label="moments", fig="table1")
    ef = R("analytic", ND + ["--v0", 1, "--times", times], threads=False, label="analytic", fig="table1")
    fine = R("analytic", ND + ["--v0", 1, "--times", "0.005:4:120"], threads=False, label="analytic curve",
             fig="table1")
    got_t = [p["time"] for p in mc["first_moment"]]
    if not np.allclose(got_t, TABLE1_TIMES, rtol=1e-9, atol=1e-12):
        raise StickslipFailure(f"moments returned times {got_t}, expected {TABLE1_TIMES}")
    ours = np.array([p["value"] for p in mc["first_moment"]])
    se = np.array([p["error"] for p in mc["first_moment"]])
    efv = values(ef["first_moment"])
    pmc = np.array(TABLE1_PAPER_MC)
    z_ef = (ours - efv) / se
    z_pmc = (ours - pmc) / se
    n = c["trajectories"]

    cols = " | ".join(f"{t:g}" for t in TABLE1_TIMES)
    lines = [
        "# Table I: first moment E[V'(t') | v_i' = 1], pure dry friction (nondimensional)",
        "",
        f"Ours: `stickslip moments` (inclusion engine, tau' = {c['tau']:g}, dt' = {c['dt']:g}, "
        f"N = {n} trajectories, X(0) ~ N(0, 1/tau'), seed {seed}), value ± standard error. "
        "EF: formula (2.11) of Touchette et al. from `stickslip analytic`. "
        "z = (ours - reference) / our standard error (the paper's numbers are rounded to 1e-3 "
        "and carry no error bar).",
        "",
        f"| t' | {cols} |",
        "|---|" + "---|" * len(TABLE1_TIMES),
        "| ours (MC) | " + " | ".join(f"{v:.4f} ± {s:.4f}" for v, s in zip(ours, se)) + " |",
        "| EF (2.11), `stickslip analytic` | " + " | ".join(f"{v:.4f}" for v in efv) + " |",
        "| z, ours vs EF | " + " | ".join(f"{z:+.2f}" for z in z_ef) + " |",
        "| paper MC (tau' = 0.5e-5) | " + " | ".join(f"{v:.3f}" for v in TABLE1_PAPER_MC) + " |",
        "| paper EF | " + " | ".join(f"{v:.3f}" for v in TABLE1_PAPER_EF) + " |",
        "| z, ours vs paper MC | " + " | ".join(f"{z:+.2f}" for z in z_pmc) + " |",
        "",
        f"max |z| vs EF = {np.max(np.abs(z_ef)):.2f}; max |z| vs the paper's MC = "
        f"{np.max(np.abs(z_pmc)):.2f}; max |paper MC - EF| = {np.max(np.abs(pmc - efv)):.4f}.",
        "",
    ]
    path = os.path.join(out, "table1.md")
    with open(path, "w") as f:
        f.write("\n".join(lines))
    written.append(path)

    fig, (ax, axr) = plt.subplots(2, 1, figsize=(7, 6.4), sharex=True,
                                  gridspec_kw={"height_ratios": [2.2, 1]})
    ax.plot(fine["times"], values(fine["first_moment"]), "r-", lw=1.4, label="EF: formula (2.11), white noise")
    ax.errorbar(TABLE1_TIMES, ours, yerr=1.96 * se, fmt="ko", ms=4, capsize=3,
                label=f"ours: colored noise, tau' = {c['tau']:g} (95% CI)")
    ax.plot(TABLE1_TIMES, pmc, "bx", ms=8, label="paper's MC (Table I)")
    ax.set_ylabel("E[V'(t') | v'_i = 1]")
    ax.set_title("Table I: first moment, pure dry friction (nondimensional)")
    ax.legend()
    ax.grid(alpha=0.3)
    axr.axhline(0, color="r", lw=1)
    axr.errorbar(TABLE1_TIMES, ours - efv, yerr=1.96 * se, fmt="ko", ms=4, capsize=3, label="ours - EF")
    axr.plot(TABLE1_TIMES, pmc - efv, "bx", ms=8, label="paper MC - EF (rounded to 1e-3)")
    axr.set_xlabel("t' (time units noise/friction^2)")
    axr.set_ylabel("difference from EF")
    axr.set_xscale("log")
    axr.legend(fontsize=8)
    axr.grid(alpha=0.3)
    fig.tight_layout()
    savefig(fig, os.path.join(out, "table1.png"), written)

    summary["table1"] = {
        "tau_nd": c["tau"], "dt_nd": c["dt"], "trajectories": n, "seed": seed,
        "times": TABLE1_TIMES,
        "ours": [rnd(v, 5) for v in ours], "stderr": [rnd(s, 2) for s in se],
        "ef": [rnd(v, 6) for v in efv], "paper_mc": TABLE1_PAPER_MC, "paper_ef": TABLE1_PAPER_EF,
        "z_vs_ef": [rnd(z, 3) for z in z_ef], "z_vs_paper_mc": [rnd(z, 3) for z in z_pmc],
        "max_abs_z_vs_ef": rnd(float(np.max(np.abs(z_ef))), 3),
        "max_abs_z_vs_paper_mc": rnd(float(np.max(np.abs(z_pmc))), 3),
        "max_abs_paper_mc_minus_ef": rnd(float(np.max(np.abs(pmc - efv))), 3),
        "steps": mc["work"].get("steps"), "sim_seconds": rnd(mc["work"]["seconds"], 3),
    }


# Figs. 2 and 3 -------------------------------------------------------------------------
def hle_split(traj):
    """Index where the first half long excursion ends (the second starts), or None."""
    p = traj["paths"][0]
    x = np.asarray(p["x"], float)
    v = np.asarray(p["v"], float)
    lo = traj["engine_details"]["lower_threshold"]
    if traj["engine"] == "pdmp":
        # s- = (x_{k- -1}, -1, 0): first lattice point below x-*, velocity 0.
        idx = np.nonzero((x < lo) & (v == 0.0))[0]
    else:
        # the -HLE restarts exactly at (x-*, 0)
        idx = np.nonzero((x == lo) & (v == 0.0))[0]
        idx = idx[idx > 0]
    return int(idx[0]) if idx.size else None


def make_fig23(R, cfg, out, written, summary, seed, only):
    c = cfg["fig23"]
    base = PAPER_B + ["--noise", 5, "--tau", 0.5]
    engines = {"pdmp": ["--engine", "pdmp", "--grid", 0.125], "inclusion": ["--engine", "inclusion"]}  # the defaults: event scheme, dt auto
    trajs, info = {}, {}
    for k, (name, eargs) in enumerate(engines.items()):
        n = c["excursions_pdmp"] if name == "pdmp" else c["excursions_incl"]
        d = R("diffusivity", base + eargs + ["--excursions", n], seed=seed,
              label=f"diffusivity {name} (mean duration)", fig="fig2")
        mean = d["mean_duration"]["value"]
        chosen = None
        for i in range(c["max_index"]):
            t = R("trajectory", base + eargs + ["--index", i, "--every", 1.0], seed=seed, threads=False,
                  label=None, fig="fig2")
            if 0.5 * mean <= t["duration"] <= 2.0 * mean:
                chosen = i
                break
        if chosen is None:
            raise StickslipFailure(f"no {name} excursion of typical length among the first {c['max_index']}")
        trajs[name] = R("trajectory", base + eargs + ["--index", chosen], seed=seed, threads=False,
                        label=f"trajectory {name} --index {chosen}", fig="fig2")
        info[name] = {"index": chosen, "seed": seed, "duration": rnd(trajs[name]["duration"], 5),
                      "displacement": rnd(trajs[name]["displacement"], 4),
                      "mean_duration": rnd(mean, 4), "mean_duration_stderr": rnd(d["mean_duration"]["error"], 2),
                      "excursions_for_mean": n}
        sp = hle_split(trajs[name])
        p = trajs[name]["paths"][0]
        info[name]["first_hle_duration"] = rnd(p["t"][sp], 5) if sp is not None else None
        info[name]["points"] = len(p["t"])

    def panels(axes, traj, title):
        p = traj["paths"][0]
        t, x, v, u = (np.asarray(p[k], float) for k in ("t", "x", "v", "u"))
        sp = hle_split(traj)
        # PDMP: X is piecewise constant between recorded events (V flows, X waits):
        # draw X(t) as steps and V against X as vertical moves then horizontal jumps.
        step = traj["engine"] == "pdmp"
        xv_x = np.repeat(x, 2)[:-1] if step else x
        xv_v = np.concatenate([[v[0]], np.repeat(v[1:], 2)]) if step else v
        segs = [(slice(0, sp + 1), "k", "first HLE"), (slice(sp, None), "r", "second HLE")] if sp else \
            [(slice(None), "k", "long excursion")]
        hi, lo = traj["engine_details"]["upper_threshold"], traj["engine_details"]["lower_threshold"]
        for s, col, lab in segs:
            axes[0].plot(t[s], x[s], col, lw=0.6, label=lab, drawstyle="steps-post" if step else "default")
            axes[1].plot(t[s], v[s], col, lw=0.6)
            axes[2].plot(t[s], u[s], col, lw=0.9)
            s2 = slice(2 * s.start if s.start else None, 2 * s.stop if s.stop else None) if step else s
            axes[3].plot(xv_x[s2], xv_v[s2], col, lw=0.4)
        for a in (axes[0],):
            a.axhline(hi, color="gray", ls="--", lw=0.7)
            a.axhline(lo, color="gray", ls=":", lw=0.7)
        axes[3].axvline(hi, color="gray", ls="--", lw=0.7, label="x* (upper threshold)")
        axes[3].axvline(lo, color="gray", ls=":", lw=0.7, label="x-* (lower threshold)")
        axes[0].set_ylabel("noise X [s$^{-1/2}$]")
        axes[1].set_ylabel("velocity V [m/s]")
        axes[2].set_ylabel("displacement U [m]")
        for a in axes[:3]:
            a.set_xlabel("t [s]")
        axes[3].set_xlabel("noise X [s$^{-1/2}$]")
        axes[3].set_ylabel("velocity V [m/s]")
        axes[0].set_title(title, fontsize=9)
        axes[0].legend(fontsize=7, loc="upper right")
        axes[3].legend(fontsize=7, loc="lower right")
        for a in axes:
            a.grid(alpha=0.3)

    params = f"tau = 0.5 s, Delta = 3.84 m/s$^2$, Gamma = 5 m$^2$/s$^3$, {B_TEXT}"
    if "fig2" in only:
        fig, ax = plt.subplots(2, 2, figsize=(10, 7))
        panels([ax[0, 0], ax[0, 1], ax[1, 0], ax[1, 1]], trajs["pdmp"],
               f"PDMP (delta = 0.125 s$^{{-1/2}}$), excursion {info['pdmp']['index']} of seed {seed}")
        fig.suptitle("Fig. 2: one long excursion of the PDMP; " + params, fontsize=10)
        fig.tight_layout()
        savefig(fig, os.path.join(out, "fig2.png"), written)
    if "fig3" in only:
        fig, ax = plt.subplots(4, 2, figsize=(10, 13))
        panels(ax[:, 0], trajs["pdmp"], f"PDMP, delta = 0.125 s$^{{-1/2}}$ (excursion {info['pdmp']['index']})")
        panels(ax[:, 1], trajs["inclusion"],
               f"differential inclusion, {INCLUSION_SCHEME} scheme, dt auto (excursion {info['inclusion']['index']})")
        fig.suptitle("Fig. 3: a long excursion, PDMP (left) and differential inclusion (right)\n" + params,
                     fontsize=10)
        fig.tight_layout()
        savefig(fig, os.path.join(out, "fig3.png"), written)
    summary["fig2_3"] = info


# Fig. 4 ------------------------------------------------------------------------------
def sweep_points(sw):
    pts = sw["points"]
    g = np.array([p["noise"] for p in pts])
    D = np.array([est(p["diffusivity"]) for p in pts])
    T = np.array([est(p["mean_duration"]) for p in pts])
    return g, D[:, 0], D[:, 1], T[:, 0], T[:, 1]


def make_fig4(R, cfg, out, written, summary, seed):
    c = cfg["fig4"]
    fig, (axD, axT) = plt.subplots(1, 2, figsize=(12, 5))
    res = {}
    for k, (tau, (gammas, n_p, n_i)) in enumerate(c["taus"].items()):
        col = TAU_COLORS[k]
        common = PAPER_B + ["--tau", tau, "--noise", ",".join(fmt(g) for g in gammas)]
        sp = R("sweep", common + ["--engine", "pdmp", "--grid", c["grid"], "--excursions", n_p],
               seed=seed + 10 * k, label=f"sweep pdmp tau={tau:g}", fig="fig4")
        si = R("sweep", common + ["--engine", "inclusion", "--excursions", n_i],  # event scheme, dt auto
               seed=seed + 10 * k + 1, label=f"sweep inclusion tau={tau:g}", fig="fig4")
        # The Kolmogorov engine at every noise of the inclusion line: no
        # sampling, each point to 1% (about 0.5 s); its E[t1] is the
        # continuum's, which the PDMP's lattice lengthens (by 4% at grid
        # 0.0625 on the Fig. 2 case, docs/kolmogorov_measurements.md).
        sk = R("sweep", common + ["--engine", "kolmogorov", "--rel-precision", c["kolmogorov_precision"]],
               label=f"sweep kolmogorov tau={tau:g}", fig="fig4")
        gp, Dp, sDp, Tp, sTp = sweep_points(sp)
        gi, Di, sDi, Ti, sTi = sweep_points(si)
        gk = np.array([p["noise"] for p in sk["points"]])
        Dk = np.array([p["diffusivity"]["value"] for p in sk["points"]])
        eDk = np.array([p["diffusivity"]["error"] for p in sk["points"]])
        Tk = np.array([p["mean_duration"]["value"] for p in sk["points"]])
        axD.plot(gk, Dk, "--", color="k", lw=0.9, zorder=4, label="Kolmogorov engine" if k == 0 else None)
        axT.plot(gk, Tk, "--", color="k", lw=0.9, zorder=4, label="Kolmogorov engine" if k == 0 else None)
        axD.plot(gi, Di, "-", color=col, lw=1.3, label=f"tau = {tau:g} s, inclusion")
        axD.fill_between(gi, Di - 1.96 * sDi, Di + 1.96 * sDi, color=col, alpha=0.2, lw=0)
        axD.errorbar(gp, Dp, yerr=1.96 * sDp, fmt="o", color=col, ms=4, capsize=2,
                     label=f"tau = {tau:g} s, PDMP")
        axT.plot(gi, Ti, "-", color=col, lw=1.3, label=f"tau = {tau:g} s, inclusion")
        axT.fill_between(gi, Ti - 1.96 * sTi, Ti + 1.96 * sTi, color=col, alpha=0.2, lw=0)
        axT.errorbar(gp, Tp, yerr=1.96 * sTp, fmt="o", color=col, ms=4, capsize=2,
                     label=f"tau = {tau:g} s, PDMP")
        zD = zscores(Dp, sDp, Di, sDi)
        zT = zscores(Tp, sTp, Ti, sTi)
        res[f"{tau:g}"] = {
            "gammas": [float(g) for g in gp], "excursions_pdmp": n_p, "excursions_inclusion": n_i,
            "D_pdmp": [rnd(v) for v in Dp], "D_pdmp_se": [rnd(v, 2) for v in sDp],
            "D_inclusion": [rnd(v) for v in Di], "D_inclusion_se": [rnd(v, 2) for v in sDi],
            "Et1_pdmp": [rnd(v) for v in Tp], "Et1_pdmp_se": [rnd(v, 2) for v in sTp],
            "Et1_inclusion": [rnd(v) for v in Ti], "Et1_inclusion_se": [rnd(v, 2) for v in sTi],
            "z_D": [rnd(z, 3) for z in zD], "z_Et1": [rnd(z, 3) for z in zT],
            "D_agreement": zsummary(zD), "Et1_agreement": zsummary(zT),
            "Et1_ratio_pdmp_over_inclusion_mean": rnd(float(np.mean(Tp / Ti)), 4),
            "D_ratio_pdmp_over_inclusion_mean": rnd(float(np.mean(Dp / Di)), 4),
            "sim_seconds_pdmp": rnd(sp["work"]["seconds"], 3), "sim_seconds_inclusion": rnd(si["work"]["seconds"], 3),
            "D_kolmogorov": [rnd(v) for v in Dk], "D_kolmogorov_error": [rnd(v, 2) for v in eDk],
            "Et1_kolmogorov": [rnd(v) for v in Tk],
            # the solver's error is far below the Monte Carlo's: z against it alone
            "z_D_inclusion_vs_kolmogorov": [rnd(z, 3) for z in (Di - Dk) / sDi] if np.array_equal(gi, gk) else None,
            "z_D_pdmp_vs_kolmogorov": [rnd(z, 3) for z in (Dp - Dk) / sDp] if np.array_equal(gp, gk) else None,
            "seconds_kolmogorov": rnd(sk["work"]["seconds"], 3),
        }
    for a in (axD, axT):
        a.set_xscale("log")
        a.set_yscale("log")
        a.set_xlabel("noise intensity Gamma [m$^2$ s$^{-3}$]")
        a.grid(alpha=0.3, which="both")
    axD.set_ylabel("diffusivity D [m$^2$/s]")
    axT.set_ylabel("mean long-excursion duration E[t1] [s]")
    axD.set_title(f"D vs Gamma (dots: PDMP, delta = 0.125; lines: inclusion, {INCLUSION_SCHEME} scheme, dt auto;\n"
                  "dashed: Kolmogorov engine, no sampling)", fontsize=9)
    axT.set_title("E[t1] vs Gamma (bands and bars: 95% CI)", fontsize=9)
    axD.legend(fontsize=7, ncol=2)
    axT.legend(fontsize=7, ncol=2)
    fig.suptitle(f"Fig. 4: {B_TEXT}, Delta = 3.84 m/s$^2$",
                 fontsize=10)
    fig.tight_layout()
    savefig(fig, os.path.join(out, "fig4.png"), written)
    summary["fig4"] = {"dt_inclusion": "auto", "scheme_inclusion": INCLUSION_SCHEME, "grid_pdmp": c["grid"], "per_tau": res}


# Fig. 5 ------------------------------------------------------------------------------
def make_fig5(R, cfg, out, written, summary, seed):
    c = cfg["fig5"]
    fig, ax = plt.subplots(figsize=(8, 5.5))
    res = {}
    for k, (tau, (n_p, n_i)) in enumerate(c["taus"].items()):
        col = TAU_COLORS[k + 1]
        common = PAPER_B + ["--tau", tau, "--noise", c["noise"], "--max-lag", c["max_lag"], "--lags", c["lags"]]
        cp = R("correlation", common + ["--engine", "pdmp", "--grid", c["grid"], "--sample-dt", c["sample_dt"],
                                        "--excursions", n_p], seed=seed + 10 * k,
               label=f"correlation pdmp tau={tau:g}", fig="fig5")
        ci = R("correlation", common + ["--engine", "inclusion", "--sample-dt", c["sample_dt"], "--excursions", n_i],
               seed=seed + 10 * k + 1, label=f"correlation inclusion tau={tau:g}", fig="fig5")
        out_k = {}
        for name, d, ls in (("pdmp", cp, "-"), ("inclusion", ci, ":")):
            nc = d["normalised_covariance"]
            r = np.array([p["lag"] for p in nc])
            h = np.array([p["value"] for p in nc])
            s = np.array([p["error"] for p in nc])
            pos = h > 0
            ax.plot(r[pos], h[pos], ls, color=col, lw=1.6 if ls == "-" else 2.0,
                    label=f"tau = {tau:g} s (tau' = {tau * DELTA ** 2 / c['noise']:.2f}), "
                          + ("PDMP" if name == "pdmp" else "inclusion"))
            lo = np.clip(h - 1.96 * s, 1e-6, None)
            ax.fill_between(r, lo, h + 1.96 * s, color=col, alpha=0.12, lw=0)
            out_k[name] = (r, h, s)
        (r, hp, sp), (_, hi, si) = out_k["pdmp"], out_k["inclusion"]
        z = zscores(hp[1:], sp[1:], hi[1:], si[1:])
        res[f"{tau:g}"] = {
            "excursions_pdmp": n_p, "excursions_inclusion": n_i, "dt_inclusion": ci["params"]["dt"],
            "lags": [rnd(x, 4) for x in r], "h_pdmp": [rnd(x, 4) for x in hp], "h_pdmp_se": [rnd(x, 2) for x in sp],
            "h_inclusion": [rnd(x, 4) for x in hi], "h_inclusion_se": [rnd(x, 2) for x in si],
            "agreement": zsummary(z),
            "h0_pdmp": rnd(est(cp["covariance"][0])[0]), "h0_inclusion": rnd(est(ci["covariance"][0])[0]),
            "h0_pdmp_se": rnd(est(cp["covariance"][0])[1], 2), "h0_inclusion_se": rnd(est(ci["covariance"][0])[1], 2),
        }
        res[f"{tau:g}"]["h0_z"] = rnd(float(zscores(res[f"{tau:g}"]["h0_pdmp"], res[f"{tau:g}"]["h0_pdmp_se"],
                                                    res[f"{tau:g}"]["h0_inclusion"],
                                                    res[f"{tau:g}"]["h0_inclusion_se"])), 3)
    ax.set_yscale("log")
    ax.set_ylim(3e-3, 1.3)
    ax.set_xlim(0, c["max_lag"])
    ax.set_xlabel("lag r [s]")
    ax.set_ylabel("h(r)/h(0),  h(r) = cov(V(t), V(t+r))")
    ax.set_title(f"Fig. 5: normalised velocity covariance, Gamma = 5 m$^2$/s$^3$, {B_TEXT}"
                 "\nsolid: PDMP (delta = 0.125), dotted: inclusion; bands: 95% CI",
                 fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    savefig(fig, os.path.join(out, "fig5.png"), written)
    summary["fig5"] = {"noise": c["noise"], "max_lag": c["max_lag"], "sample_dt": c["sample_dt"],
                       "scheme_inclusion": INCLUSION_SCHEME, "per_tau": res}


# Fig. 6 ------------------------------------------------------------------------------
def make_fig6(R, cfg, out, written, summary, seed):
    c = cfg["fig6"]
    model = PAPER_B + ["--noise", c["noise"]]
    lo, hi = c["range"]
    d = R("density", model + ["--tau", c["tau"], "--scheme", "resolvent", "--dt", c["dt"], "--excursions", c["excursions"],
                              f"--range={lo!r},{hi!r}", "--bins", c["bins"]], seed=seed, label="density", fig="fig6")
    bins = d["histogram"]["bins"]
    blo = np.array([b["lo"] for b in bins])
    bhi = np.array([b["hi"] for b in bins])
    dens = np.array([b["value"] for b in bins])
    se = np.array([b["error"] for b in bins])
    mid = 0.5 * (blo + bhi)
    _, pbar = bin_average(R, model, float(blo[0]), float(bhi[-1]), len(bins), fig="fig6")
    curve = R("analytic", model + [f"--velocities={even_grid(lo, hi, 481)}"], threads=False,
              label="analytic curve", fig="fig6")
    paths = R("trajectory", model + ["--tau", c["tau"], "--scheme", "resolvent", "--dt", c["path_dt"], "--paths", c["paths"],
                                     "--time", c["path_time"], "--every", c["path_time"] / 1000],
              seed=seed + 1, threads=False, label="trajectory --paths", fig="fig6")
    stuck = est(d["stuck_probability"])
    z = zscores(dens, se, pbar)
    zs = zsummary(z[se > 0])
    ref = R("analytic", model, threads=False, label="analytic", fig="fig6")

    fig = plt.figure(figsize=(12, 6))
    gs = fig.add_gridspec(2, 2, height_ratios=[3, 1])
    ax = fig.add_subplot(gs[0, 0])
    axz = fig.add_subplot(gs[1, 0], sharex=ax)
    ax2 = fig.add_subplot(gs[:, 1])
    ok = se > 0
    axz.plot(mid[ok], z[ok], "r^", ms=3)
    axz.axhline(0, color="k", lw=1)
    for lev in (-2, 2):
        axz.axhline(lev, color="gray", ls=":", lw=0.8)
    axz.set_xlabel("velocity v [m/s]")
    axz.set_ylabel("z = (hist - P) / se")
    axz.grid(alpha=0.3)
    plt.setp(ax.get_xticklabels(), visible=False)
    ax.plot(curve["velocities"], curve["stationary_density"], "k-", lw=1.3,
            label="Hayakawa P(v) (white noise), `stickslip analytic`")
    ax.errorbar(mid, dens, yerr=1.96 * se, fmt="r^", ms=3.5, capsize=1.5, lw=0.8,
                label=f"histogram, tau = {c['tau']:g} s, dt = {c['dt']:g} s (95% CI)")
    ax.set_ylabel("stationary density [s/m]")
    ax.set_title(f"Fig. 6 left: bin width {bhi[0] - blo[0]:.2g} m/s, {c['excursions']} long excursions;\n"
                 f"P(stuck) = {stuck[0]:.2e} ± {stuck[1]:.1e} (atom at v = 0, not in the histogram); "
                 f"max |z| = {zs.get('max_abs_z')}", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    for k, p in enumerate(paths["paths"]):
        ax2.plot(p["t"], p["u"], lw=0.9)
    ax2.set_xlabel("t [s]")
    ax2.set_ylabel("displacement U(t) [m]")
    ax2.set_title(f"Fig. 6 right: {len(paths['paths'])} paths of U(t) from (X, V) = (x*, 0), dt = {c['path_dt']:g} s;\n"
                  f"white-noise mean drift M0 = {ref['mobility']['value']:.2e} m/s", fontsize=9)
    ax2.grid(alpha=0.3)
    fig.suptitle("Fig. 6: tau = 1e-5 s, Gamma = 0.16 m$^2$/s$^3$, Delta = 3.84 m/s$^2$, %s (tau' = %.2g)"
                 % (B_TEXT, c["tau"] * DELTA ** 2 / c["noise"]), fontsize=10)
    fig.tight_layout()
    savefig(fig, os.path.join(out, "fig6.png"), written)
    u_end = np.array([p["u"][-1] for p in paths["paths"]])
    summary["fig6"] = {
        "tau": c["tau"], "noise": c["noise"], "dt": c["dt"], "excursions": c["excursions"],
        "bins": len(bins), "bin_width": rnd(float(bhi[0] - blo[0]), 3),
        "stuck_probability": rnd(stuck[0]), "stuck_probability_se": rnd(stuck[1], 2),
        "histogram_vs_hayakawa": zs,
        "mean": rnd(est(d["mean"])[0]), "mean_se": rnd(est(d["mean"])[1], 2),
        "variance": rnd(est(d["variance"])[0]), "variance_se": rnd(est(d["variance"])[1], 2),
        "white_noise_mobility": rnd(ref["mobility"]["value"]), "white_noise_variance": rnd(ref["variance"]["value"]),
        "z_mean": rnd(float(zscores(est(d["mean"])[0], est(d["mean"])[1], ref["mobility"]["value"])), 3),
        "z_variance": rnd(float(zscores(est(d["variance"])[0], est(d["variance"])[1], ref["variance"]["value"])), 3),
        "paths_U_at_end": [rnd(float(u), 3) for u in u_end],
    }


# Fig. 7 ------------------------------------------------------------------------------
def make_fig7(R, cfg, out, written, summary, seed):
    c = cfg["fig7"]
    lo, hi = c["range"]
    times = ",".join(fmt(t) for t in c["times"])
    curve = R("analytic", ND + ["--v0", 1, "--times", times, f"--velocities={even_grid(lo, hi, 561)}"],
              threads=False, label="analytic curve", fig="fig7")
    fig, axes = plt.subplots(2, 2, figsize=(12, 9), sharex=True)
    res = {}
    tcols = plt.cm.viridis(np.linspace(0, 0.85, len(c["times"])))
    pbar = None
    for k, tau in enumerate(c["taus"]):
        ax = axes.flat[k]
        m = R("moments", ND + ["--tau", tau, "--scheme", "resolvent", "--dt", c["dt"], "--v0", 1, "--times", times, "--density",
                               "--bins", c["bins"], f"--range={lo!r},{hi!r}", "--trajectories", c["trajectories"]],
              seed=seed + k, label=f"moments --density tau'={tau:g}", fig="fig7")
        if pbar is None:
            b0 = m["density"][0]["bins"]
            _, pbar = bin_average(R, ND, float(b0[0]["lo"]), float(b0[-1]["hi"]), len(b0),
                                  extra=["--v0", 1, "--times", times], key="transient_density", fig="fig7")
        per_t = []
        for j, h in enumerate(m["density"]):
            bl = np.array([b["lo"] for b in h["bins"]])
            bh = np.array([b["hi"] for b in h["bins"]])
            dens = np.array([b["value"] for b in h["bins"]])
            se = np.array([b["error"] for b in h["bins"]])
            ax.plot(curve["velocities"], curve["transient_density"][j], "r-", lw=1.1,
                    label="(2.10), white noise" if j == 0 else None)
            ax.stairs(dens, np.append(bl, bh[-1]), color=tcols[j], lw=1.2,
                      label=f"t' = {h['time']:g}, P(stuck) = {h['stuck_probability']['value']:.3f}")
            ok = se > 0
            z = zscores(dens[ok], se[ok], pbar[j][ok])
            l1 = float(np.sum(np.abs(dens - pbar[j]) * (bh - bl)))
            per_t.append({"time": h["time"], "stuck": rnd(h["stuck_probability"]["value"]),
                          "stuck_se": rnd(h["stuck_probability"]["error"], 2), "l1_distance": rnd(l1, 3), **zsummary(z)})
        fm = m["first_moment"]
        ax.set_title(f"tau' = {tau:g}  (dt' = {c['dt']:g}, N = {c['trajectories']})", fontsize=10)
        ax.set_xlim(lo, hi)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        if k >= 2:
            ax.set_xlabel("v' (velocity units noise/friction)")
        if k % 2 == 0:
            ax.set_ylabel("p(v', t' | v'_i = 1)")
        res[f"{tau:g}"] = {"per_time": per_t,
                           "first_moment": [rnd(p["value"], 4) for p in fm],
                           "first_moment_se": [rnd(p["error"], 2) for p in fm]}
    fig.suptitle("Fig. 7: transient velocity density from v'_i = 1, X(0) ~ N(0, 1/tau'), pure dry friction "
                 "(nondimensional)\nred: formula (2.10) (white noise); steps: colored-noise histograms "
                 "(the atom at v' = 0 is left out of the histogram)", fontsize=10)
    fig.tight_layout()
    savefig(fig, os.path.join(out, "fig7.png"), written)
    summary["fig7"] = {"dt_nd": c["dt"], "trajectories": c["trajectories"], "times": c["times"],
                       "bins": c["bins"], "range": list(c["range"]), "per_tau": res}


# Fig. 8 ------------------------------------------------------------------------------
def make_fig8(R, cfg, out, written, summary, seed):
    c = cfg["fig8"]
    fine_t = ",".join(fmt(x) for x in np.linspace(0, c["max_lag"], 201))
    curve = R("analytic", ND + ["--times", fine_t], threads=False, label="analytic curve", fig="fig8")
    fig, (ax, axr) = plt.subplots(2, 1, figsize=(8, 8), sharex=True, gridspec_kw={"height_ratios": [2.2, 1]})
    ax.plot(curve["times"], values(curve["autocorrelation"]), "r-", lw=1.6, label="(2.13), white noise", zorder=5)
    res = {}
    markers = ["o", "s", "^", "v"]
    for k, (tau, n) in enumerate(c["taus"].items()):
        col = TAU_COLORS[k]
        d = R("correlation", ND + ["--tau", tau, "--scheme", "resolvent", "--dt", c["dt"], "--max-lag", c["max_lag"], "--lags", c["lags"],
                                   "--excursions", n], seed=seed + k, label=f"correlation tau'={tau:g}", fig="fig8")
        ac = d["autocorrelation"]
        r = np.array([p["lag"] for p in ac])
        v = np.array([p["value"] for p in ac])
        s = np.array([p["error"] for p in ac])
        ref = R("analytic", ND + ["--times", ",".join(fmt(x) for x in r)], threads=False,
                label=None, fig="fig8")
        cref = values(ref["autocorrelation"])
        pos = v > 0
        ax.errorbar(r[pos], v[pos], yerr=1.96 * s[pos], fmt=markers[k], color=col, ms=3.5, capsize=1.5, lw=0.7,
                    label=f"tau' = {tau:g}, N = {n}")
        axr.errorbar(r + (k - 1.5) * 0.02, v - cref, yerr=1.96 * s, fmt=markers[k], color=col, ms=3, capsize=1,
                     lw=0.6)
        z = zscores(v, s, cref)
        res[f"{tau:g}"] = {"excursions": n, "stop_rule": d.get("stop_rule"),
                           "lags": [rnd(x, 4) for x in r], "C": [rnd(x, 4) for x in v],
                           "C_se": [rnd(x, 2) for x in s], "C_ref": [rnd(x, 4) for x in cref],
                           "C0": rnd(v[0], 4), "C0_se": rnd(s[0], 2), **zsummary(z)}
    ax.set_yscale("log")
    ax.set_ylim(5e-3, 0.8)
    ax.set_ylabel("<V'(t') V'(0)>")
    ax.set_title(f"Fig. 8: stationary autocorrelation, pure dry friction (nondimensional), dt' = {c['dt']:g};"
                 " bars: 95% CI", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    axr.axhline(0, color="r")
    axr.set_xlabel("t' (time units noise/friction^2)")
    axr.set_ylabel("simulation - (2.13)")
    axr.grid(alpha=0.3)
    fig.tight_layout()
    savefig(fig, os.path.join(out, "fig8.png"), written)
    summary["fig8"] = {"dt_nd": c["dt"], "max_lag": c["max_lag"], "per_tau": res}


# Fig. 9 ------------------------------------------------------------------------------
def make_fig9(R, cfg, out, written, summary, seed):
    c = cfg["fig9"]
    fig, axes = plt.subplots(2, 2, figsize=(13, 9.5), sharex=True, gridspec_kw={"height_ratios": [2.2, 1]})
    res = {}
    gw = np.exp(np.linspace(np.log(min(c["gammas"])), np.log(max(c["gammas"])), c["white_points"]))
    for bi, (bname, bargs, title) in enumerate((
            ("b=0", ZERO_B, "b(v) = 0"),
            ("paper_b", PAPER_B, B_TEXT))):
        ax, axr = axes[0, bi], axes[1, bi]
        white = np.array([R("analytic", bargs + ["--noise", g], threads=False, label=None, fig="fig9")["diffusivity"]["value"]
                          for g in gw])
        wfit = np.polyfit(np.log(gw), np.log(white), 1)[0]
        ax.plot(gw, white, "k--", lw=1.3, label=f"white noise (quadrature), slope {wfit:.2f}")
        axr.axhline(1.0, color="k", ls="--", lw=1.2)
        rb = {"white_noise_gammas": [rnd(g) for g in gw], "white_noise_D": [rnd(x) for x in white],
              "white_noise_exponent": rnd(float(wfit), 4), "per_tau": {}}
        ntau = len(c["taus"])
        kolmogorov_labelled = False
        for k, (tau, ns) in enumerate(c["taus"].items()):
            n = ns[bi]
            col = TAU_COLORS[k]
            sw = R("sweep", bargs + ["--tau", tau, "--noise", ",".join(fmt(g) for g in c["gammas"]),
                                  "--scheme", "resolvent", "--dt", c["dt"],
                                     "--excursions", n], seed=seed + 100 * bi + 10 * k,
                   label=f"sweep {bname} tau={tau:g} (N={n})", fig="fig9")
            g, D, sD, T, sT = sweep_points(sw)
            ex = sw["exponents"][0]
            alpha, salpha = est(ex["exponent"])
            ax.plot(g, D, "-", color=col, lw=1.4,
                    label=f"tau = {tau:g} s: long excursions (N = {n}), alpha = {alpha:.2f} ± {salpha:.2f}")
            ax.fill_between(g, D - 1.96 * sD, D + 1.96 * sD, color=col, alpha=0.2, lw=0)
            white_at = np.array([R("analytic", bargs + ["--noise", gg], threads=False, label=None,
                                   fig="fig9")["diffusivity"]["value"] for gg in g])
            shift = np.exp((k - (ntau - 1) / 2) * 0.012)  # small horizontal offsets in the ratio panel
            axr.errorbar(g * shift, D / white_at, yerr=1.96 * sD / white_at, fmt="-", color=col, lw=1.2,
                         capsize=2)
            bf = []
            for j, gb in enumerate(c["bf_gammas"]):
                b = R("bruteforce", bargs + ["--tau", tau, "--noise", gb, "--scheme", "resolvent", "--dt", c["dt"], "--time", c["bf_time"],
                                            "--v0", 0, "--trajectories", c["bf_trajectories"]],
                      seed=seed + 100 * bi + 10 * k + 1 + j, label=f"bruteforce {bname} tau={tau:g} Gamma={gb:g}",
                      fig="fig9")
                bf.append((gb, *est(b["diffusivity"])))
            bf = np.array(bf)
            ax.errorbar(bf[:, 0], bf[:, 1], yerr=1.96 * bf[:, 2], fmt="o", color=col, ms=5, mfc="none", capsize=2)
            # long-excursion D at the brute-force Gammas (same grid points)
            idx = [int(np.argmin(np.abs(g - gb))) for gb in bf[:, 0]]
            axr.errorbar(bf[:, 0] * shift, bf[:, 1] / white_at[idx], yerr=1.96 * bf[:, 2] / white_at[idx], fmt="o",
                         color=col, ms=5, mfc="none", capsize=2)
            zbf = zscores(bf[:, 1], bf[:, 2], D[idx], sD[idx])
            rb["per_tau"][f"{tau:g}"] = {
                "excursions": n, "stop_rule": sw["points"][0].get("stop_rule"),
                "tau_nd": [rnd(p["nondimensional"]["tau"], 3) for p in sw["points"]],
                "gammas": [float(x) for x in g], "D": [rnd(x) for x in D], "D_se": [rnd(x, 2) for x in sD],
                "Et1": [rnd(x) for x in T],
                "exponent": rnd(alpha, 4), "exponent_se": rnd(salpha, 2),
                "exponent_chi2_per_dof": rnd(ex.get("chi2_per_dof"), 3) if ex.get("chi2_per_dof") is not None else None,
                "exponent_minus_3_in_se": rnd((alpha - 3) / salpha, 3) if salpha > 0 else None,
                "exponent_minus_white_in_se": rnd((alpha - wfit) / salpha, 3) if salpha > 0 else None,
                "local_slopes": [rnd(p["slope"]["value"], 3) for p in sw["points"]],
                "D_over_white": [rnd(x, 4) for x in D / white_at],
                "z_vs_white": [rnd(x, 3) for x in zscores(D, sD, white_at)],
                "bruteforce": {"gammas": [float(x) for x in bf[:, 0]], "D_t": [rnd(x) for x in bf[:, 1]],
                               "D_t_se": [rnd(x, 2) for x in bf[:, 2]],
                               "D_t_over_D": [rnd(x, 4) for x in bf[:, 1] / D[idx]],
                               "D_t_over_white": [rnd(x, 4) for x in bf[:, 1] / white_at[idx]],
                               "z_vs_long_excursions": [rnd(x, 3) for x in zbf]},
                "sim_seconds": rnd(sw["work"]["seconds"], 3),
            }
            # The Kolmogorov engine at every point (a line with squares, its estimated
            # error as the bar): one solved sweep over the noises of this tau (below
            # tau' = 0.1 its near-white discretisation, down to the white limit).
            precision = ["--rel-precision", c["kolmogorov_precision"]] if "kolmogorov_precision" in c else []
            sk = R("sweep", bargs + ["--engine", "kolmogorov", "--tau", tau,
                                     "--noise", ",".join(fmt(gg) for gg in c["gammas"])] + precision,
                   label=f"sweep kolmogorov {bname} tau={tau:g}", fig="fig9")
            Dk = np.array([p["diffusivity"]["value"] for p in sk["points"]])
            eDk = np.array([p["diffusivity"]["error"] for p in sk["points"]])
            ax.errorbar(g, Dk, yerr=eDk, fmt="s:", color=col, mfc=col, mec="k", ms=5, lw=1.0, capsize=2, zorder=5,
                        label="Kolmogorov engine (squares, dotted)" if not kolmogorov_labelled else None)
            axr.errorbar(g * shift, Dk / white_at, yerr=eDk / white_at, fmt="s:", color=col, mfc=col, mec="k", ms=5,
                         lw=1.0, capsize=2, zorder=5)
            kolmogorov_labelled = True
            rb["per_tau"][f"{tau:g}"]["kolmogorov"] = {
                "gammas": [float(x) for x in g], "D": [rnd(x) for x in Dk], "D_error": [rnd(x, 2) for x in eDk],
                "D_over_white": [rnd(x, 6) for x in Dk / white_at],
                "exponent": rnd(sk["exponents"][0]["exponent"]["value"], 5) if sk["exponents"] else None,
                "z_long_excursions_vs_kolmogorov": [rnd(x, 3) for x in zscores(D, sD, Dk)],
                "seconds": rnd(sk["work"]["seconds"], 3)}
        ax.plot([], [], "o", color="gray", mfc="none", label=f"brute force, t = {c['bf_time']:g} s, V(0) = 0 "
                                                              f"(N' = {c['bf_trajectories']})")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylabel("diffusivity D [m$^2$/s]")
        ax.set_title(f"{title}\nDelta = 3.84 m/s$^2$, dt = {c['dt']:g} s; bands and bars: 95% CI", fontsize=9)
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3, which="both")
        axr.set_xscale("log")
        axr.set_xlabel("noise intensity Gamma [m$^2$ s$^{-3}$]")
        axr.set_ylabel("D / D(white noise)")
        axr.grid(alpha=0.3, which="both")
        res[bname] = rb
    fig.suptitle("Fig. 9: D vs Gamma, long-excursion estimator (lines), brute force (circles), "
                 "Kolmogorov engine (squares), white-noise limit (dashed)", fontsize=10)
    fig.tight_layout()
    savefig(fig, os.path.join(out, "fig9.png"), written)
    summary["fig9"] = {"dt": c["dt"], "bf_time": c["bf_time"], "bf_trajectories": c["bf_trajectories"], **res}


# Main ------------------------------------------------------------------------------
def user_args():
    """The command-line arguments the user gave the wrapper (without --bin/--root)."""
    args, skip = [], False
    for x in sys.argv[1:]:
        if skip:
            skip = False
            continue
        if x in ("--bin", "--root"):
            skip = True
            continue
        if x.startswith("--bin=") or x.startswith("--root="):
            continue
        args.append(x)
    return args


def main():
    ap = argparse.ArgumentParser(prog="scripts/figures",
                                 description="Regenerate Table I and Figs. 2-9 of the paper with stickslip.")
    ap.add_argument("--bin", required=True, help="stickslip binary")
    ap.add_argument("--root", required=True, help="repository root")
    ap.add_argument("--quick", action="store_true", help="CI smoke run: tiny sizes, rough plots (~2 min)")
    ap.add_argument("--out", help="output folder (default docs/figures; with --quick build/figures-quick)")
    ap.add_argument("--only", help="comma-separated subset of " + ",".join(FIGURES))
    ap.add_argument("--threads", type=int, default=2, help="worker threads per stickslip call (default 2)")
    ap.add_argument("--seed", type=int, default=1, help="base random seed (default 1)")
    ap.add_argument("--cache", help="reuse/store raw stickslip JSON results in this folder (development)")
    ap.add_argument("--drift", metavar="EXPR",
                    help="a drift law b(v) (stickslip's --drift, SI units) in place of the paper's -v/tauL + gbar "
                         "in the figures built on it (" + ",".join(DRIFT_FIGURES) + "; the default with --drift); "
                         "written to build/figures-drift unless --out says otherwise")
    ap.add_argument("--drift-params", metavar="NAME=NUM,...", default="",
                    help="values of the named constants of --drift")
    ap.add_argument("--static-friction-ratio", metavar="R", type=float,
                    help="run every figure with a static friction R times its friction (R >= 1; stickslip's "
                         "--static-friction); written to build/figures-static unless --out says otherwise")
    a = ap.parse_args()

    only = FIGURES if not a.only else [s.strip() for s in a.only.split(",") if s.strip()]
    bad = [s for s in only if s not in FIGURES]
    if bad:
        ap.error(f"unknown figure(s) {bad}; choose from {FIGURES}")
    if a.drift_params and not a.drift:
        ap.error("--drift-params needs --drift")
    if a.drift:
        if not a.only:
            only = DRIFT_FIGURES
        dry = [s for s in only if s not in DRIFT_FIGURES]
        if dry:
            ap.error(f"{','.join(dry)} are pure dry friction (b = 0): --drift does not enter them; "
                     f"choose from {','.join(DRIFT_FIGURES)}")
        use_drift_law(a.drift, a.drift_params)
    ratio = a.static_friction_ratio
    if ratio is not None:
        if not (math.isfinite(ratio) and ratio >= 1.0):
            ap.error(f"--static-friction-ratio must be a finite number >= 1 (the static friction over the "
                     f"friction), not {ratio:g}")
        use_static_friction(ratio)
    if a.threads < 1:
        ap.error("--threads must be >= 1")
    if a.out:
        out = a.out
    elif a.drift:  # the paper's figures (docs/, build/figures-quick/) keep the paper's law
        out = os.path.join(a.root, "build", "figures-drift-quick" if a.quick else "figures-drift")
    elif ratio is not None:
        out = os.path.join(a.root, "build", "figures-static-quick" if a.quick else "figures-static")
    elif a.quick:  # CI smoke runs never touch docs/
        out = os.path.join(a.root, "build", "figures-quick")
    else:
        out = os.path.join(a.root, "docs", "figures")
    out = os.path.abspath(out)
    os.makedirs(out, exist_ok=True)
    cfg = QUICK if a.quick else DEFAULT
    R = Runner(a.bin, a.threads, cache_dir=a.cache)

    version = subprocess.run([a.bin, "--version"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True).stdout.strip()
    summary_path = os.path.join(out, "summary.json")
    summary = {}
    if a.only and os.path.exists(summary_path):
        with open(summary_path) as f:
            summary = json.load(f)
        # Figures of another drift law or static friction are not merged with these: start afresh.
        meta = summary.get("meta", {})
        if (meta.get("drift", PAPER_DRIFT), meta.get("drift_params", ""), meta.get("static_friction_ratio")) != \
                (a.drift or PAPER_DRIFT, a.drift_params, ratio):
            summary = {}
    timing = summary.get("timing_seconds", {}) if a.only else {}
    written = []
    jobs = [("table1", ["table1"], lambda: make_table1(R, cfg, out, written, summary, a.seed)),
            ("fig2+fig3", ["fig2", "fig3"], lambda: make_fig23(R, cfg, out, written, summary, a.seed + 20, only)),
            ("fig4", ["fig4"], lambda: make_fig4(R, cfg, out, written, summary, a.seed + 40)),
            ("fig5", ["fig5"], lambda: make_fig5(R, cfg, out, written, summary, a.seed + 80)),
            ("fig6", ["fig6"], lambda: make_fig6(R, cfg, out, written, summary, a.seed + 120)),
            ("fig7", ["fig7"], lambda: make_fig7(R, cfg, out, written, summary, a.seed + 140)),
            ("fig8", ["fig8"], lambda: make_fig8(R, cfg, out, written, summary, a.seed + 160)),
            ("fig9", ["fig9"], lambda: make_fig9(R, cfg, out, written, summary, a.seed + 200))]
    t_all = time.perf_counter()
    print(f"[figures] {'quick' if a.quick else 'default'} run, {a.threads} threads, binary {a.bin} ({version}), "
          f"output {out}", file=sys.stderr, flush=True)
    try:
        for name, figs, fn in jobs:
            if not any(f in only for f in figs):
                continue
            print(f"[figures] {name} ...", file=sys.stderr, flush=True)
            t0 = time.perf_counter()
            fn()
            dt = time.perf_counter() - t0
            timing[name] = round(dt, 1)
            print(f"[figures] {name}: {dt:.1f} s", file=sys.stderr, flush=True)
    except StickslipFailure as e:
        print(f"[figures] ERROR: {e}", file=sys.stderr)
        sys.exit(1)
    total = time.perf_counter() - t_all
    summary["timing_seconds"] = timing
    summary["meta"] = {
        "command": " ".join(["bash", "scripts/figures"] + [shlex.quote(x) for x in user_args()]),
        "mode": "quick" if a.quick else "default", "only": only if (a.only or a.drift) else "all",
        "drift": a.drift or PAPER_DRIFT, "drift_params": a.drift_params, "static_friction_ratio": ratio,
        "threads": a.threads, "seed": a.seed, "stickslip_version": version,
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "cpus": os.cpu_count(), "seconds_this_run": round(total, 1),
        "cached": bool(a.cache),
    }
    summary["warnings"] = {k: sorted(v) for k, v in R.warnings.items()} | \
        ({k: v for k, v in summary.get("warnings", {}).items() if k not in R.warnings} if a.only else {})
    with open(summary_path, "w") as f:
        json.dump(summary, f, indent=1)
    written.append(summary_path)
    print(f"[figures] done in {total:.1f} s ({R.calls} stickslip calls). Files written:", file=sys.stderr)
    for p in written:
        print(f"  {p}", file=sys.stderr)


if __name__ == "__main__":
    main()
