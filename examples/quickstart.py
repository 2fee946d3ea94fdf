#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Quick start of the stickslip Python module: the diffusivity D against the
noise intensity Gamma for two correlation times, with the exact white-noise
curve.

Run it with Debian's Python, which has NumPy and Matplotlib (a `python3` first
on PATH, e.g. pyenv's, may have neither):

    /usr/bin/python3 examples/quickstart.py                 # writes quickstart.png here
    /usr/bin/python3 examples/quickstart.py --out /tmp/d.png --excursions 5000   # quicker

`import stickslip` works after `bash scripts/build.sh` (which pip-installs the
module for /usr/bin/python3), or from the build tree with
PYTHONPATH=build/python. About a minute on 2 cores with the defaults (PDMP
engine, 20000 long excursions per point, 12 points); --excursions 5000 is 4x faster.

Everything is in SI units: friction, relaxation and bias are the paper's Fig. 2
case (3.84 m/s^2, 0.067 s, 0.342 m/s^2); Gamma runs over 3..10 m^2/s^3 for
tau = 0.125 s and 0.5 s. The dashed line is the exact white-noise D (the
limit tau -> 0, by quadrature of Hayakawa's density): coloured noise makes the
object stick for longer, so D falls below it, the more so the longer tau.
"""
import argparse
import time

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.ticker  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import stickslip  # noqa: E402
from stickslip import analytic  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="quickstart.png", help="PNG to write (default: quickstart.png)")
    ap.add_argument("--excursions", type=int, default=20000, help="long excursions per point (default 20000)")
    ap.add_argument("--engine", default="pdmp", choices=["pdmp", "inclusion"],
                    help="pdmp (exact, lattice noise; default) or inclusion (time stepping: the event scheme at its automatic step)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--threads", type=int, default=0, help="worker threads (0: the CPUs this process may use)")
    args = ap.parse_args()

    fig2 = stickslip.Params()                  # friction 3.84, relaxation 0.067, bias 0.342 (SI)
    noises = stickslip.logspace(3, 10, 6)      # Gamma [m^2/s^3], log-spaced like the CLI's 3:10:6
    taus = [0.125, 0.5]                        # [s]

    start = time.monotonic()
    # One call runs every (tau, Gamma) point, each with its own random streams;
    # Ctrl-C stops it cleanly. Points are tau-major: reshape to (len(taus), len(noises)).
    r = stickslip.sweep(fig2, noise=noises, tau=taus, engine=args.engine, excursions=args.excursions,
                        seed=args.seed, threads=args.threads, progress=True)
    seconds = time.monotonic() - start
    D = r.diffusivity.value.reshape(r.shape)
    lo = r.diffusivity.lo.reshape(r.shape)
    hi = r.diffusivity.hi.reshape(r.shape)

    # The exact white-noise reference on a fine grid (no simulation, milliseconds).
    fine = np.geomspace(noises[0], noises[-1], 60)
    white = np.array([analytic.white_noise_reference(fig2.replace(noise=g, tau=0.0))["diffusivity"] for g in fine])

    print(f"{'tau [s]':>8} {'Gamma [m^2/s^3]':>16} {'D [m^2/s]':>12} {'95% interval':>25} {'white D':>11}")
    for i, tau in enumerate(r.taus):
        for j, g in enumerate(r.noises):
            w = analytic.white_noise_reference(fig2.replace(noise=g, tau=0.0))["diffusivity"]
            print(f"{tau:8.3g} {g:16.4g} {D[i, j]:12.4e}   [{lo[i, j]:.3e}, {hi[i, j]:.3e}] {w:11.4e}")
    for e in r.exponents:
        print(f"tau = {e.tau:g} s: D ~ Gamma^alpha with alpha = {e.exponent.value:.2f} +- "
              f"{e.exponent.stderr:.2f} (chi^2/dof {e.chi2_per_dof:.2f})")
    print(f"{args.excursions} {args.engine} excursions per point, {seconds:.1f} s")

    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    for i, tau in enumerate(r.taus):
        ax.errorbar(r.noises, D[i], yerr=[D[i] - lo[i], hi[i] - D[i]], fmt="o-", ms=4, capsize=3,
                    label=f"$\\tau$ = {tau:g} s ({args.engine})")
    ax.plot(fine, white, "k--", lw=1.2, label="white noise, exact")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xticks([3, 4, 5, 6, 8, 10])
    ax.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel(r"noise intensity $\Gamma$ [m$^2$ s$^{-3}$]")
    ax.set_ylabel(r"diffusivity $D$ [m$^2$ s$^{-1}$]")
    ax.set_title("Dry friction under coloured noise (Fig. 2 friction, drag, bias)", fontsize=10)
    ax.legend(frameon=False)
    ax.grid(True, which="both", alpha=0.25)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
