# SPDX-License-Identifier: BSD-3-Clause
"""Params, Scales, Estimate; errors carry the CLI's messages."""
import math
import pickle
import unittest

import stickslip
from _support import cli_error


class ImportTest(unittest.TestCase):
    def test_public_names(self):
        for name in stickslip.__all__:
            self.assertTrue(hasattr(stickslip, name), name)
        self.assertEqual(stickslip.__version__.count("."), 2)
        self.assertTrue(issubclass(stickslip.InvalidParameterError, ValueError))
        self.assertTrue(issubclass(stickslip.CappedExcursionsError, stickslip.UntrustworthyResultError))
        self.assertTrue(issubclass(stickslip.UntrustworthyResultError, RuntimeError))

    def test_help_teaches_units(self):
        doc = stickslip.diffusivity.__doc__
        for text in ("[m^2/s]", "dt : float", "[s]", "Fig. 2", "excursions : int", "KeyboardInterrupt"):
            self.assertIn(text, doc)
        self.assertIn("noise/2", stickslip.Params.__doc__)


class ParamsTest(unittest.TestCase):
    def test_defaults_are_fig2(self):
        p = stickslip.Params()
        self.assertEqual((p.friction, p.noise, p.tau, p.relaxation, p.bias), (3.84, 5.0, 0.5, 0.067, 0.342))
        self.assertFalse(p.white)
        self.assertTrue(p.has_stationary_state)
        self.assertAlmostEqual(p.force_amplitude, math.sqrt(2.5))
        self.assertAlmostEqual(p.upper_threshold, (3.84 - 0.342) / math.sqrt(2.5))

    def test_round_trips(self):
        p = stickslip.Params(friction=2, noise=3, tau=0.25, relaxation=float("inf"), bias=-0.5)
        self.assertEqual(stickslip.Params(**p.to_dict()), p)
        self.assertEqual(pickle.loads(pickle.dumps(p)), p)
        self.assertEqual(eval(repr(p), {"Params": stickslip.Params}), p)
        self.assertEqual(hash(p), hash(stickslip.Params(**p.to_dict())))
        q = p.replace(tau=0)
        self.assertTrue(q.white)
        self.assertEqual(q.replace(tau=0.25), p)
        self.assertNotEqual(q, p)
        with self.assertRaises(TypeError):
            p.replace(gamma=1)
        with self.assertRaises(AttributeError):
            p.tau = 1.0  # immutable

    def test_nondimensional(self):
        p = stickslip.Params()
        s = p.scales()
        nd = p.nondimensional()
        self.assertEqual((nd.friction, nd.noise), (1.0, 1.0))
        self.assertAlmostEqual(s.time, 5 / 3.84**2)
        self.assertAlmostEqual(s.velocity, 5 / 3.84)
        self.assertAlmostEqual(s.length, 25 / 3.84**3)
        self.assertAlmostEqual(s.diffusivity, 125 / 3.84**4)
        self.assertAlmostEqual(nd.tau, 0.5 / s.time)
        self.assertAlmostEqual(nd.relaxation, 0.067 / s.time)
        self.assertAlmostEqual(nd.bias, 0.342 / 3.84)
        back = stickslip.Params.from_nondimensional(nd, 3.84, 5.0)
        for k, v in p.to_dict().items():
            self.assertAlmostEqual(getattr(back, k), v, places=12)
        inf = stickslip.Params(relaxation=float("inf")).nondimensional()
        self.assertTrue(math.isinf(inf.relaxation))
        self.assertEqual(set(s.to_dict()), {"time", "length", "velocity", "acceleration", "diffusivity",
                                            "noise_level"})

    def test_invalid_values(self):
        with self.assertRaises(stickslip.InvalidParameterError) as c:
            stickslip.Params(friction=-1)
        self.assertEqual(c.exception.parameter, "friction")
        self.assertEqual(str(c.exception), "--friction: " + c.exception.message)
        with self.assertRaises(ValueError) as c:
            stickslip.Params(noise=float("nan"))
        self.assertEqual(str(c.exception), "--noise: noise must be a number, got NaN")
        with self.assertRaises(TypeError):
            stickslip.Params(3.84)  # keyword-only


class CliMessagesTest(unittest.TestCase):
    """str(ValueError) is exactly the CLI's error line without 'stickslip: error: '."""

    def check(self, cli_args, call):
        expected = cli_error(*cli_args)
        with self.assertRaises(ValueError) as c:
            call()
        self.assertEqual(str(c.exception), expected)

    def test_physics(self):
        self.check(["diffusivity", "--friction=-1"], lambda: stickslip.Params(friction=-1))
        self.check(["diffusivity", "--relaxation=0"], lambda: stickslip.Params(relaxation=0))
        self.check(["diffusivity", "--tau=-0.5"], lambda: stickslip.Params(tau=-0.5))

    def test_run_settings(self):
        self.check(["diffusivity", "--excursions", "1"], lambda: stickslip.diffusivity(excursions=1))
        self.check(["diffusivity", "--excursions=-5"], lambda: stickslip.diffusivity(excursions=-5))
        self.check(["diffusivity", "--dt", "0"], lambda: stickslip.diffusivity(dt=0))
        self.check(["diffusivity", "--engine", "euler"], lambda: stickslip.diffusivity(engine="euler"))
        self.check(["diffusivity", "--stop-rule", "paper"], lambda: stickslip.diffusivity(stop_rule="paper"))
        self.check(["diffusivity", "--level", "1.5"], lambda: stickslip.diffusivity(level=1.5))
        self.check(["diffusivity", "--threads", "5000"], lambda: stickslip.diffusivity(threads=5000))
        self.check(["diffusivity", "--seed=-1"], lambda: stickslip.diffusivity(seed=-1))
        self.check(["diffusivity", "--estimator", "mean"], lambda: stickslip.diffusivity(estimator="mean"))
        self.check(["diffusivity", "--engine", "pdmp", "--tau", "0"],
                   lambda: stickslip.diffusivity(stickslip.Params(tau=0), engine="pdmp"))
        self.check(["diffusivity", "--relaxation", "inf", "--bias", "4"],
                   lambda: stickslip.diffusivity(stickslip.Params(relaxation=float("inf"), bias=4)))

    def test_observables(self):
        self.check(["density", "--bins", "0"], lambda: stickslip.density(bins=0))
        self.check(["correlation", "--max-lag=-1"], lambda: stickslip.correlation(max_lag=-1))
        self.check(["moments", "--times=-1"], lambda: stickslip.moments(times=[-1]))
        self.check(["trajectory", "--paths", "2000"], lambda: stickslip.trajectory(paths=2000))
        self.check(["bruteforce", "--time", "0"], lambda: stickslip.bruteforce(time=0))


class EstimateTest(unittest.TestCase):
    def test_estimate(self):
        r = stickslip.diffusivity(stickslip.Params(), engine="pdmp", excursions=64, threads=1)
        e = r.diffusivity
        self.assertEqual(e.ci, (e.lo, e.hi))
        self.assertLess(e.lo, e.value)
        self.assertLess(e.value, e.hi)
        self.assertEqual(float(e), e.value)
        self.assertEqual(e.level, 0.95)
        self.assertEqual(pickle.loads(pickle.dumps(e)).to_dict(), e.to_dict())
        self.assertIn("Estimate(value=", repr(e))


if __name__ == "__main__":
    unittest.main()
