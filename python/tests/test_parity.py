# SPDX-License-Identifier: BSD-3-Clause
"""Python and the command give the same numbers for the same settings: for every
simulating or solving subcommand, with only non-default arguments given on both sides,
to_dict() equals the CLI's JSON less "work"."""
import unittest

import stickslip
from _support import cli_json, without_work

# (function, CLI flags, Python keywords); the model parameters go in params.
CASES = [
    ("diffusivity", ["--excursions", "128", "--dt", "2e-3", "--seed", "5", "--level", "0.9", "--estimator", "paper"],
     dict(excursions=128, dt=2e-3, seed=5, level=0.9, estimator="paper")),
    ("diffusivity", ["--excursions", "64", "--dt", "2e-3", "--rel-precision", "0.3", "--max-excursions", "500"],
     dict(excursions=64, dt=2e-3, rel_precision=0.3, max_excursions=500)),
    ("bruteforce", ["--time", "1.5", "--trajectories", "100", "--dt", "1e-3", "--x0", "0.2", "--v0", "0.1"],
     dict(time=1.5, trajectories=100, dt=1e-3, x0=0.2, v0=0.1)),
    ("density", ["--excursions", "64", "--dt", "2e-3", "--bins", "9", "--range=-1,1", "--stop-rule", "stuck"],
     dict(excursions=64, dt=2e-3, bins=9, range=(-1, 1), stop_rule="stuck")),
    ("density", ["--engine", "pdmp", "--excursions", "64", "--sample-dt", "2e-3", "--grid", "0.25"],
     dict(engine="pdmp", excursions=64, sample_dt=2e-3, grid=0.25)),
    ("correlation", ["--excursions", "64", "--dt", "2e-3", "--lags", "4", "--max-lag", "0.2"],
     dict(excursions=64, dt=2e-3, lags=4, max_lag=0.2)),
    ("moments", ["--trajectories", "100", "--dt", "1e-3", "--times", "0.1,0.3", "--density", "--v0", "0.4"],
     dict(trajectories=100, dt=1e-3, times=[0.1, 0.3], density=True, v0=0.4)),
    ("moments", ["--trajectories", "100", "--dt", "1e-3", "--density"], dict(trajectories=100, dt=1e-3, density=True)),
    ("trajectory", ["--dt", "1e-2", "--index", "2", "--every", "0.5"], dict(dt=1e-2, index=2, every=0.5)),
    ("trajectory", ["--paths", "2", "--time", "0.3", "--dt", "1e-3", "--every", "0.1", "--threads", "1"],
     dict(paths=2, time=0.3, dt=1e-3, every=0.1, threads=1)),
    ("sweep", ["--noise", "2,4", "--tau", "0.5", "--excursions", "64", "--dt", "2e-3"],
     dict(noise=[2, 4], tau=[0.5], excursions=64, dt=2e-3)),
    ("spectrum", ["--frequencies", "0,1", "--rel-precision", "0.05"], dict(frequencies=[0, 1], rel_precision=0.05)),
    ("spectrum", ["--engine", "inclusion", "--excursions", "200", "--frequencies", "0,1,10"],
     dict(engine="inclusion", excursions=200, frequencies=[0, 1, 10])),
]

PARAMS = stickslip.Params(friction=3.84, noise=5, tau=0.5, relaxation=0.067, bias=0.342)


class ParityTest(unittest.TestCase):
    def test_every_subcommand(self):
        for function, flags, keywords in CASES:
            with self.subTest(function=function, flags=flags):
                cli = cli_json(function, *flags)
                py = getattr(stickslip, function)(PARAMS, **keywords).to_dict()
                self.assertEqual(without_work(py), without_work(cli))

    def test_white_noise_references(self):
        p = stickslip.Params(friction=2, noise=3, relaxation=0.5, bias=0.4)
        cli = cli_json("analytic", "--friction", "2", "--noise", "3", "--relaxation", "0.5", "--bias", "0.4",
                       "--v0", "0.5", "--times", "0.1,1", "--velocities=-1,0,1")
        py = stickslip.analytic.white_noise(p, v0=0.5, times=[0.1, 1], velocities=[-1, 0, 1]).to_dict()
        self.assertEqual(without_work(py), without_work(cli))


if __name__ == "__main__":
    unittest.main()
