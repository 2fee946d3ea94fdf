# SPDX-License-Identifier: BSD-3-Clause
"""stickslip.analytic: vectorised closed forms against known values and the CLI."""
import math
import unittest

import numpy as np

import stickslip
from stickslip import analytic
from _support import cli_json, without_work

# Pure dry friction, nondimensional (friction = noise = 1): closed forms.
PURE = stickslip.Params(friction=1, noise=1, tau=0, relaxation=float("inf"), bias=0)
FIG2 = stickslip.Params()
trapz = getattr(np, "trapezoid", None) or np.trapz  # NumPy 2 renamed it
TABLE_I_T = [0.05, 0.125, 0.25, 0.5, 1.0, 2.5]
TABLE_I = [0.950000, 0.875248, 0.757249, 0.567963, 0.336204, 0.090194]


class ClosedFormTest(unittest.TestCase):
    def test_table_i(self):
        m = analytic.first_moment(PURE, TABLE_I_T, 1.0)
        self.assertEqual(m.shape, (6,))
        np.testing.assert_allclose(m, TABLE_I, atol=5e-7)

    def test_reference_five_quarters(self):
        ref = analytic.white_noise_reference(PURE)
        self.assertAlmostEqual(ref["diffusivity"], 1.25, places=10)
        self.assertAlmostEqual(ref["mobility"], 0.0, places=10)
        self.assertAlmostEqual(ref["variance"], 0.5, places=10)
        self.assertAlmostEqual(analytic.dry_friction_diffusivity(PURE), 1.25, places=12)
        self.assertEqual(analytic.dry_friction_mobility(PURE), 0.0)
        self.assertTrue(analytic.is_pure_dry_friction(PURE))
        self.assertFalse(analytic.is_pure_dry_friction(FIG2))
        self.assertAlmostEqual(analytic.viscous_diffusivity(FIG2), 0.067**2 * 5)

    def test_autocorrelation(self):
        c = analytic.autocorrelation(PURE, np.array([0.0, 1.0, -1.0]))
        self.assertAlmostEqual(c[0], 0.5, places=10)  # Var(V)
        self.assertEqual(c[1], c[2])  # even
        t = np.linspace(0, 40, 40001)
        green_kubo = 2 * trapz(analytic.autocorrelation(PURE, t), t)
        self.assertAlmostEqual(green_kubo, 1.25, places=4)

    def test_broadcasting_and_scalars(self):
        t = np.array([[0.1], [0.5], [1.0]])       # (3, 1)
        v0 = np.array([0.0, 0.5, 1.0, 2.0])       # (4,)
        m = analytic.first_moment(PURE, t, v0)
        self.assertEqual(m.shape, (3, 4))
        self.assertAlmostEqual(m[1, 2], analytic.first_moment(PURE, 0.5, 1.0))
        self.assertIsInstance(analytic.first_moment(PURE, 0.5, 1.0), float)
        self.assertEqual(analytic.autocorrelation(PURE, np.zeros((2, 5))).shape, (2, 5))
        v = np.linspace(-4, 4, 801)
        p = analytic.propagator(PURE, v[:, None], np.array([0.25, 1.0]), 1.0)
        self.assertEqual(p.shape, (801, 2))
        np.testing.assert_allclose(trapz(p, v, axis=0), 1.0, atol=2e-3)
        self.assertEqual(analytic.hayakawa_density(FIG2, np.zeros((2, 3, 4))).shape, (2, 3, 4))

    def test_hayakawa(self):
        self.assertAlmostEqual(analytic.hayakawa_probability(FIG2, -np.inf, np.inf), 1.0, places=12)
        v = np.linspace(-6, 6, 120001)
        p = analytic.hayakawa_density(FIG2, v)
        self.assertAlmostEqual(trapz(p, v), 1.0, places=6)
        mom = analytic.hayakawa_moments(FIG2)
        ref = analytic.white_noise_reference(FIG2)
        self.assertAlmostEqual(mom["mean"], ref["mobility"], places=12)
        self.assertAlmostEqual(mom["variance"], ref["variance"], places=12)
        self.assertAlmostEqual(trapz(v * p, v), mom["mean"], places=6)
        phi = analytic.hayakawa_potential(FIG2, [mom["mode"], 1.0])
        self.assertEqual(phi[0], 0.0)
        self.assertGreater(phi[1], 0.0)
        a = np.array([-1.0, 0.0])
        b = np.array([0.0, 1.0])
        self.assertEqual(analytic.hayakawa_probability(FIG2, a, b).shape, (2,))

    def test_dry_friction_closed_forms_demand_pure_friction(self):
        with self.assertRaises(stickslip.InvalidParameterError) as c:
            analytic.first_moment(PURE, -1.0, 1.0)
        self.assertEqual(c.exception.parameter, "time")
        with self.assertRaises(ValueError) as c:
            analytic.white_noise_reference(stickslip.Params(relaxation=float("inf"), bias=5))
        self.assertTrue(str(c.exception).startswith("--bias: "))


class FokkerPlanckTest(unittest.TestCase):
    def test_general_drift(self):
        # With drag and bias the transient quantities come from the Fokker-Planck solver.
        m = analytic.first_moment(FIG2, [0.0, 0.05, 20.0], 1.0)
        self.assertAlmostEqual(m[0], 1.0, places=9)
        self.assertLess(m[1], 1.0)
        self.assertAlmostEqual(m[2], analytic.white_noise_reference(FIG2)["mobility"], places=5)
        c = analytic.autocorrelation(FIG2, [0.0, 0.1])
        self.assertEqual(c.shape, (2,))
        v = np.linspace(-3, 3, 601)
        p = analytic.propagator(FIG2, v, 0.2, 0.5)
        self.assertAlmostEqual(trapz(p, v), 1.0, places=3)

    def test_solver_object(self):
        fp = analytic.FokkerPlanck(FIG2)
        self.assertGreater(fp.cell_width, 0)
        self.assertEqual(fp.density(0.5, np.array([0.1, 0.2]), np.linspace(-1, 1, 5)).shape, (2, 5))


class WhiteNoiseTest(unittest.TestCase):
    def test_equals_cli_json(self):
        r = analytic.white_noise(PURE, v0=1.0, times=[0, 0.5, 1], velocities=[-1, 0, 1])
        cli = cli_json("analytic", "--friction", "1", "--noise", "1", "--relaxation", "inf", "--bias", "0",
                       "--v0", "1", "--times", "0,0.5,1", "--velocities", "-1:1:3")
        self.assertEqual(without_work(r.to_dict()), without_work(cli))  # less the command: a call, a command line
        self.assertEqual(r.transient_density.shape, (3, 3))
        self.assertTrue(np.all(np.isnan(r.transient_density[0])))
        self.assertEqual(r.first_moment.shape, (3,))
        self.assertAlmostEqual(r.diffusivity, 1.25, places=10)
        self.assertIn("closed form", r.method)
        fig2 = analytic.white_noise(FIG2, times=[0.5])
        self.assertIn("fokker-planck", fig2.method)
        self.assertTrue(math.isfinite(fig2.first_moment.value[0]))
        self.assertEqual(fig2.first_moment.kind, "solved")  # the grid's discretisation error
        self.assertEqual(r.first_moment.kind, "exact")


if __name__ == "__main__":
    unittest.main()
