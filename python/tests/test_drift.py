# SPDX-License-Identifier: BSD-3-Clause
"""A drift law b(v) from Python: drift= takes an expression, a callable or two
arrays; the law reaches every engine that runs it and the exact white-noise
references; a law that does not confine is refused when Params is made."""
import unittest

import numpy as np

import stickslip
import stickslip.analytic as analytic


class DriftLawTest(unittest.TestCase):
    def test_expression_callable_and_arrays_give_the_same_law(self):
        expr = stickslip.Params(friction=1, noise=1, tau=0, drift="0.5 - v/2")
        func = stickslip.Params(friction=1, noise=1, tau=0, drift=lambda v: 0.5 - v / 2)
        table = stickslip.Params(friction=1, noise=1, tau=0,
                                 drift=(np.array([-1.0, 1.0]), np.array([1.0, 0.0])))
        affine = stickslip.Params(friction=1, noise=1, tau=0, relaxation=2, bias=0.5)
        want = analytic.white_noise_reference(affine)
        for p in (expr, func, table):
            got = analytic.white_noise_reference(p)
            self.assertAlmostEqual(got["diffusivity"] / want["diffusivity"], 1.0, delta=1e-9)
            self.assertAlmostEqual(got["mobility"] / want["mobility"], 1.0, delta=1e-9)
        self.assertEqual(expr.drift, "0.5 - v/2")
        self.assertIn("drift='0.5 - v/2'", repr(expr))
        self.assertNotIn("relaxation", repr(expr))

    def test_a_law_runs_on_the_pdmp_and_the_density_is_the_quadratures(self):
        p = stickslip.Params(friction=1, noise=1, tau=1, drift="0.3 - v*abs(v)")
        r = stickslip.diffusivity(p, excursions=2000, engine="pdmp", grid=0.2, threads=2)
        self.assertGreater(r.diffusivity.value, 0)
        white = stickslip.Params(friction=1, noise=1, tau=0, drift="0.3 - v*abs(v)")
        dens = analytic.hayakawa_density(white, np.linspace(-3, 3, 601))
        self.assertAlmostEqual(float(np.sum(dens[1:] + dens[:-1]) * 0.005), 1.0, delta=1e-4)

    def test_a_callable_law_runs_the_event_scheme_with_coloured_noise(self):
        # The default scheme for coloured noise is the event scheme, which takes any law
        # (each piece's exact laws); its D agrees with the PDMP's within the errors.
        p = stickslip.Params(friction=1, noise=1, tau=1, drift=lambda v: 0.1 - v / 2)
        r = stickslip.diffusivity(p, excursions=4000, seed=3, threads=2)
        self.assertEqual(r.meta["settings"]["scheme"], "event")
        q = stickslip.diffusivity(p, excursions=4000, seed=4, threads=2, engine="pdmp", grid=0.1)
        a, b = r.diffusivity, q.diffusivity
        z = (a.value - b.value) / np.hypot(a.stderr, b.stderr)
        self.assertLess(abs(z), 4.0, f"event vs pdmp: D {a.value} vs {b.value}, z = {z:.2f}")

    def test_a_sweep_varies_a_named_constant_on_a_first_axis(self):
        # Params needs a value for c to make the law: a placeholder, replaced per point.
        p = stickslip.Params(friction=1, noise=1, tau=1, drift="a*v - c*v^3", drift_params="a=0.5,c=1")
        r = stickslip.sweep(p, vary="c", vary_values=[0.5, 0.25], noise=[1, 2], tau=[1],
                            engine="kolmogorov", rel_precision=0.01, progress=False)
        self.assertEqual(r.shape, (2, 1, 2))
        self.assertEqual(r.vary, "c")
        np.testing.assert_array_equal(r.vary_values, [0.25, 0.5])
        np.testing.assert_array_equal(r.varied[:, 0, 0], [0.25, 0.5])
        np.testing.assert_array_equal(r.noise[1, 0], [1, 2])
        self.assertEqual(np.asarray(r.diffusivity).shape, (2, 1, 2))
        # Point (1, 0, 1) is the diffusivity run at c = 0.5, noise 2.
        one = stickslip.diffusivity(stickslip.Params(friction=1, noise=2, tau=1, drift="a*v - c*v^3",
                                                     drift_params="a=0.5,c=0.5"),
                                    engine="kolmogorov", rel_precision=0.01)
        self.assertEqual(r.diffusivity[1, 0, 1].value, one.diffusivity.value)
        self.assertEqual([e.varied for e in r.exponents], [0.25, 0.5])
        with self.assertRaisesRegex(ValueError, "--vary: .*not a constant"):
            stickslip.sweep(p, vary="b", vary_values=[1], noise=[1], tau=[1], engine="kolmogorov")

    def test_bad_laws_are_refused(self):
        with self.assertRaisesRegex(ValueError, "--drift: .*does not confine"):
            stickslip.Params(drift="v")
        with self.assertRaisesRegex(ValueError, "--drift: .*names 'x'"):
            stickslip.Params(drift="x*v")
        with self.assertRaisesRegex(ValueError, "--drift"):
            stickslip.Params(drift=(np.array([1.0, -1.0]), np.array([0.0, 1.0])))


if __name__ == "__main__":
    unittest.main()
