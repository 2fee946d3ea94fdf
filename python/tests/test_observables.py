# SPDX-License-Identifier: BSD-3-Clause
"""density(), correlation(), moments(), trajectory(), sweep(): documented shapes, the CLI's JSON."""
import math
import unittest

import numpy as np

import stickslip
from _support import cli_json, without_work

P = stickslip.Params()


class DensityTest(unittest.TestCase):
    def test_shapes_and_cli_json(self):
        r = stickslip.density(P, engine="pdmp", excursions=128, bins=20, seed=2)
        self.assertEqual(r.edges.shape, (21,))
        self.assertEqual(r.centers.shape, (20,))
        self.assertEqual(r.density.value.shape, (20,))
        self.assertEqual(r.density.ci.shape, (20, 2))
        self.assertEqual(len(r.density), 20)
        self.assertIsInstance(r.density[3], stickslip.Estimate)
        np.testing.assert_array_equal(np.asarray(r.density), r.density.value)
        total = np.sum(r.density.value * np.diff(r.edges)) + r.stuck_probability.value + r.below.value + r.above.value
        self.assertAlmostEqual(total, 1.0, places=9)
        self.assertGreater(r.stuck_probability.value, 0)  # coloured noise: the object sticks
        self.assertEqual(r.histogram.edges.shape, (21,))
        self.assertEqual(r.completed, 128)
        cli = cli_json("density", "--engine", "pdmp", "--excursions", "128", "--bins", "20", "--seed", "2")
        self.assertEqual(without_work(r.to_dict()), without_work(cli))
        # the same excursions as diffusivity()'s plain estimator (density has no control variate)
        d = stickslip.diffusivity(P, engine="pdmp", excursions=128, seed=2, control_variate="off")
        self.assertEqual(r.diffusivity.value, d.diffusivity.value)

    def test_range(self):
        r = stickslip.density(P, engine="pdmp", excursions=64, bins=10, range=(-2, 2), threads=1)
        self.assertEqual((r.edges[0], r.edges[-1]), (-2.0, 2.0))
        with self.assertRaises(ValueError):
            stickslip.density(P, range=(2, -2))


class CorrelationTest(unittest.TestCase):
    def test_shapes_and_cli_json(self):
        r = stickslip.correlation(P, engine="pdmp", excursions=128, max_lag=0.5, lags=10, seed=4)
        self.assertEqual(r.lag.shape, (11,))
        for s in (r.autocorrelation, r.covariance, r.normalised_covariance):
            self.assertEqual(s.value.shape, (11,))
            self.assertEqual(s.ci.shape, (11, 2))
        self.assertAlmostEqual(r.normalised_covariance.value[0], 1.0)
        self.assertEqual(r.normalised.value.tolist(), r.normalised_covariance.value.tolist())  # the former name
        self.assertAlmostEqual(r.lag[-1], 0.5)
        cli = cli_json("correlation", "--engine", "pdmp", "--excursions", "128", "--max-lag", "0.5", "--lags", "10",
                       "--seed", "4")
        self.assertEqual(without_work(r.to_dict()), without_work(cli))


class MomentsTest(unittest.TestCase):
    def test_defaults_are_the_cli_defaults(self):
        r = stickslip.moments(P, engine="pdmp", trajectories=128, seed=9)
        self.assertEqual(r.time.shape, (6,))
        self.assertAlmostEqual(r.v0, P.scales().velocity)
        self.assertAlmostEqual(r.first_moment.value[0], r.v0, delta=0.3 * r.v0)
        self.assertEqual(r.density, [])
        cli = cli_json("moments", "--engine", "pdmp", "--trajectories", "128", "--seed", "9")
        self.assertEqual(without_work(r.to_dict()), without_work(cli))

    def test_density(self):
        r = stickslip.moments(P, engine="pdmp", times=np.array([0.5, 0.1]), v0=0.5, trajectories=128, density=True,
                              bins=12, threads=1)
        self.assertEqual(list(r.time), [0.1, 0.5])  # sorted
        self.assertEqual(len(r.density), 2)
        h = r.density[1]
        self.assertIsInstance(h, stickslip.Histogram)
        self.assertEqual(h.edges.shape, (13,))
        self.assertEqual(h.density.value.shape, (12,))
        self.assertEqual(r.second_moment.value.shape, (2,))
        self.assertEqual(r.stuck_probability.value.shape, (2,))


class TrajectoryTest(unittest.TestCase):
    def test_excursion(self):
        r = stickslip.trajectory(P, engine="pdmp", seed=3, index=2)
        self.assertEqual(len(r.paths), 1)
        path = r.path
        n = len(path)
        for col in (path.t, path.x, path.v, path.u):
            self.assertEqual(col.shape, (n,))
            self.assertEqual(col.dtype, np.float64)
        self.assertEqual(path.mode.shape, (n,))
        self.assertTrue(set(np.unique(path.mode)) <= {-1, 0, 1})
        self.assertTrue(r.complete)
        self.assertAlmostEqual(path.t[-1], r.duration, delta=1e-9 * max(1.0, r.duration))
        # Every number of the JSON's excursion under its JSON name.
        d = r.to_dict()
        for name in ("displacement", "duration", "first_half_duration", "complete"):
            self.assertEqual(getattr(r, name), d[name], name)
        self.assertTrue(0 < r.first_half_duration < r.duration)
        cli = cli_json("trajectory", "--engine", "pdmp", "--seed", "3", "--index", "2")
        self.assertEqual(without_work(r.to_dict()), without_work(cli))

    def test_paths(self):
        r = stickslip.trajectory(P, paths=3, time=0.5, every=0.01, threads=1)
        self.assertEqual(len(r.paths), 3)
        for p in r.paths:
            self.assertEqual(set(p.to_dict()), {"t", "x", "mode", "v", "u"})
            self.assertAlmostEqual(p.t[-1], 0.5, delta=1.3e-7)  # the event scheme's clock: dt/2^16 = 2.6e-7 s


class SweepTest(unittest.TestCase):
    def test_shapes_and_cli_json(self):
        r = stickslip.sweep(P, noise=stickslip.logspace(3, 10, 3), tau=[0.5, 0.25], engine="pdmp", excursions=64,
                            seed=6)
        self.assertEqual(r.shape, (2, 3))
        self.assertEqual(list(r.taus), [0.25, 0.5])
        self.assertEqual(r.diffusivity.value.shape, (2, 3))  # (n_tau, n_noise): axis 0 taus, axis 1 noises
        self.assertEqual(list(r.noise[0]), list(r.noises))
        self.assertEqual(r.tau.tolist(), [[0.25] * 3, [0.5] * 3])
        self.assertEqual(r.slope.value.shape, (2, 3))
        self.assertEqual(len(r.exponents), 2)
        self.assertTrue(math.isfinite(r.exponents[0].exponent.value))
        cli = cli_json("sweep", "--noise", "3:10:3", "--tau", "0.5,0.25", "--engine", "pdmp", "--excursions", "64",
                       "--seed", "6")
        self.assertEqual(without_work(r.to_dict()), without_work(cli))
        # a point is a diffusivity() run with its own streams
        self.assertEqual(len(r.stop_rule), 6)


if __name__ == "__main__":
    unittest.main()
