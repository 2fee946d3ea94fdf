# SPDX-License-Identifier: BSD-3-Clause
"""diffusivity() and bruteforce(): attributes, the CLI's JSON, thread independence."""
import contextlib
import io
import unittest

import stickslip
from _support import cli_json, without_work

P = stickslip.Params()


class DiffusivityTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.r = stickslip.diffusivity(P, excursions=192, seed=7, threads=2)

    def test_attributes(self):
        r = self.r
        for e in (r.diffusivity, r.mobility, r.mean_duration):
            self.assertIsInstance(e, stickslip.Estimate)
            self.assertGreater(e.stderr, 0)
            self.assertEqual(len(e.ci), 2)
        self.assertGreater(r.diffusivity.value, 0)
        self.assertEqual(r.completed, 192)
        self.assertEqual(r.capped, 0)
        self.assertEqual(r.excursions, 192)
        self.assertEqual((r.engine, r.estimator, r.stop_rule, r.seed, r.level), ("inclusion", "renewal", "exact", 7, 0.95))
        self.assertEqual(r.params, P)
        self.assertGreater(r.work, 0)
        # The run's own diagnosis (the pilot's tail of D's influence function)
        # replaces the general note on few excursions; without the pilot it stays.
        self.assertEqual(r.control_variate["influence"]["excursions"], 768)
        self.assertFalse(r.control_variate["influence"]["flagged"])
        self.assertFalse(any("fewer than 5000" in w for w in r.warnings))
        unpiloted = stickslip.diffusivity(P, excursions=192, seed=7, threads=2, control_variate_pilot=0)
        self.assertTrue(any("fewer than 5000" in w for w in unpiloted.warnings))
        self.assertIn("DiffusivityResult(", repr(r))
        d = r.to_dict()
        self.assertEqual(d["diffusivity"]["value"], r.diffusivity.value)
        self.assertEqual(d["diffusivity"]["ci"], list(r.diffusivity.ci))
        self.assertEqual(d["warnings"], r.warnings)
        self.assertIn("diffusivity D", r.to_table())
        self.assertTrue(r.to_csv().count("\n") >= 2)

    def test_equals_cli_json(self):
        cli = cli_json("diffusivity", "--excursions", "192", "--seed", "7", "--threads", "2")
        self.assertEqual(without_work(self.r.to_dict()), without_work(cli))

    def test_pdmp_equals_cli_json(self):
        p = stickslip.Params(relaxation=float("inf"), bias=0.5)
        r = stickslip.diffusivity(p, engine="pdmp", grid=0.25, excursions=256, seed=3, level=0.9)
        cli = cli_json("diffusivity", "--engine", "pdmp", "--grid", "0.25", "--excursions", "256", "--seed", "3",
                       "--level", "0.9", "--relaxation", "inf", "--bias", "0.5")
        self.assertEqual(without_work(r.to_dict()), without_work(cli))
        self.assertEqual(r.to_dict()["params"]["relaxation"], "inf")

    def test_precision_on_demand_equals_cli(self):
        r = stickslip.diffusivity(P, scheme="resolvent", dt=1e-3, excursions=256, rel_precision=0.15, seed=5)
        self.assertTrue(r.precision["reached"])
        self.assertLessEqual(r.precision["relative_half_width"], 0.15)
        self.assertIsNone(self.r.precision)
        cli = cli_json("diffusivity", "--scheme", "resolvent", "--dt", "1e-3", "--excursions", "256", "--rel-precision", "0.15",
                       "--seed", "5")
        self.assertEqual(without_work(r.to_dict()), without_work(cli))

    def test_threads_do_not_change_the_result(self):
        one = stickslip.diffusivity(P, engine="pdmp", excursions=640, seed=11, threads=1)
        two = stickslip.diffusivity(P, engine="pdmp", excursions=640, seed=11, threads=2)
        self.assertEqual(one.threads, 1)
        self.assertEqual(two.threads, 2)
        self.assertEqual(two.threads_from, "option")
        self.assertEqual(two.to_dict()["work"]["threads_from"], "option")
        self.assertEqual(without_work(one.to_dict()), without_work(two.to_dict()))
        self.assertEqual(one.diffusivity.value, two.diffusivity.value)

    def test_paper_estimator_and_white_noise(self):
        white = stickslip.Params(friction=1, noise=1, tau=0, relaxation=float("inf"), bias=0)
        r = stickslip.diffusivity(white, scheme="resolvent", dt=1e-3, excursions=128, estimator="paper", threads=1)
        self.assertEqual(r.stop_rule, "velocity-levels")
        self.assertEqual(r.estimator, "paper")

    def test_white_noise_event_scheme(self):
        # The event scheme at its automatic step against the exact quadrature
        # (drag 0.2 and bias 0.3: D's standard error is 0.9% at 20000 excursions).
        white = stickslip.Params(friction=1, noise=1, tau=0, relaxation=0.2, bias=0.3)
        r = stickslip.diffusivity(white, scheme="event", dt="auto", excursions=20000, seed=3)
        exact = stickslip.analytic.white_noise_reference(white)
        self.assertEqual((r.stop_rule, r.to_dict()["params"]["dt"]), ("velocity-levels", 0.2 / 16))
        for name in ("diffusivity", "mobility"):
            e = getattr(r, name)
            z = (e.value - exact[name]) / e.stderr
            self.assertLess(abs(z), 4, f"{name}: {e.value} vs {exact[name]}, z = {z:.2f}")
        with self.assertRaises(stickslip.InvalidParameterError) as c:
            stickslip.density(white, scheme="event", excursions=64)
        self.assertEqual(c.exception.parameter, "scheme")

    def test_capped(self):
        with self.assertRaises(stickslip.CappedExcursionsError) as c:
            stickslip.diffusivity(P, scheme="resolvent", dt=1e-4, excursions=64, max_steps=50000, threads=1)
        self.assertIn("runaway guard", str(c.exception))
        r = stickslip.diffusivity(P, scheme="resolvent", dt=1e-4, excursions=64, max_steps=50000, threads=1,
                                  allow_capped=True)
        self.assertGreater(r.capped, 0)
        self.assertEqual(r.completed + r.capped, 64)

    def test_near_white_noise_at_a_tiny_step_raises_not_nan(self):
        # tau' = 1e-8 at dt = 1e-10: the discrete chain's excursions all end
        # within their first step (D would be 0/0), the resolved ones last
        # hours: refused up front naming tau, or untrustworthy; never a number.
        fast = stickslip.Params(friction=1, noise=1, tau=1e-8, relaxation=float("inf"), bias=0)
        with self.assertRaises((stickslip.InvalidParameterError, stickslip.UntrustworthyResultError)) as c:
            stickslip.diffusivity(fast, scheme="resolvent", dt=1e-10, excursions=64, threads=1)
        if isinstance(c.exception, stickslip.InvalidParameterError):
            self.assertEqual(c.exception.parameter, "tau")
            self.assertIn("this run would take", str(c.exception))
        else:
            self.assertNotIsInstance(c.exception, stickslip.CappedExcursionsError)
            self.assertIn("first step", str(c.exception))

    def test_level_too_close_to_one_is_invalid_not_overflow(self):
        with self.assertRaises(stickslip.InvalidParameterError) as c:
            stickslip.diffusivity(P, excursions=64, level=0.9999999999999999)
        self.assertEqual(c.exception.parameter, "level")

    def test_check_dt(self):
        r = stickslip.diffusivity(P, scheme="event", dt=0.03, excursions=2048, check_dt=True, threads=1)
        c = r.discretisation
        self.assertEqual((c["dt"], c["check_dt"], c["excursions"]), (0.03, 0.06, 2048))
        self.assertGreater(c["diffusivity"]["error"], 0)
        self.assertEqual(r.to_dict()["discretisation"]["mobility"]["value"], c["mobility"]["value"])
        self.assertIsNone(stickslip.diffusivity(P, dt=0.03, excursions=64, threads=1).discretisation)

    def test_dt_auto(self):
        # Fig. 2 case, event scheme: relaxation/8 = 0.008375 s; twice that for the check.
        r = stickslip.diffusivity(P, scheme="event", dt="auto", excursions=256, check_dt=True, threads=1)
        d = r.to_dict()
        self.assertEqual((d["params"]["dt"], d["params"]["dt_auto"]), (0.008375, True))
        self.assertEqual(r.discretisation["check_dt"], 2 * 0.008375)
        cli = cli_json("diffusivity", "--scheme", "event", "--dt", "auto", "--excursions", "256", "--check-dt",
                       "--threads", "1")
        self.assertEqual(without_work(d), without_work(cli))
        with self.assertRaises(stickslip.InvalidParameterError) as c:
            stickslip.diffusivity(P, dt="fast", excursions=64)
        self.assertEqual(c.exception.parameter, "dt")

    def test_progress_line(self):
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            stickslip.diffusivity(P, engine="pdmp", excursions=128, threads=1, progress=True)
        self.assertIn("640/640 excursions", err.getvalue())  # 128 and the pilot of 4 x 128
        self.assertTrue(err.getvalue().endswith("\n"))

    def test_params_as_dict_and_default(self):
        r = stickslip.diffusivity({"tau": 0.5}, engine="pdmp", excursions=64, threads=1)
        self.assertEqual(r.params, P)
        with self.assertRaises(TypeError):
            stickslip.diffusivity("fig2")


class BruteForceTest(unittest.TestCase):
    def test_equals_cli_json(self):
        r = stickslip.bruteforce(P, engine="pdmp", time=2, trajectories=200, seed=5)
        cli = cli_json("bruteforce", "--engine", "pdmp", "--time", "2", "--trajectories", "200", "--seed", "5")
        self.assertEqual(without_work(r.to_dict()), without_work(cli))
        self.assertEqual(r.trajectories, 200)
        self.assertEqual(r.time, 2.0)
        self.assertGreater(r.diffusivity.value, 0)
        self.assertAlmostEqual(r.x0, r.to_dict()["params"]["x0"])

    def test_start(self):
        r = stickslip.bruteforce(P, time=0.5, trajectories=64, x0=0.0, v0=0.1, threads=1)
        self.assertEqual(r.x0, 0.0)
        self.assertEqual(r.v0, 0.1)


if __name__ == "__main__":
    unittest.main()
