# SPDX-License-Identifier: BSD-3-Clause
"""diffusivity(engine="kolmogorov") and sweep(engine="kolmogorov"): the grid
solver's D, M0, P(V = 0) and E[t1], each
with its estimated discretisation error and no standard error; the engines it
does not serve refuse it."""
import unittest

import numpy as np

import stickslip


class KolmogorovEngineTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # A loose precision: one round of grids, well under a second.
        cls.r = stickslip.diffusivity(engine="kolmogorov", rel_precision=0.01)

    def test_values_with_discretisation_errors(self):
        r = self.r
        for e in (r.diffusivity, r.mobility, r.stuck_probability, r.mean_duration):
            self.assertIsInstance(e, stickslip.GridEstimate)
            self.assertGreater(e.error, 0)
            self.assertLess(e.error, abs(e.value))
        self.assertLess(r.diffusivity.error, 0.01 * r.diffusivity.value)
        self.assertEqual(r.method, "kolmogorov")
        self.assertEqual(float(r.diffusivity), r.diffusivity.value)

    def test_json_has_value_and_error_of_kind_solved(self):
        d = self.r.to_dict()
        self.assertEqual(d["engine"], "kolmogorov")
        for key in ("diffusivity", "mobility", "stuck_probability", "mean_duration"):
            self.assertEqual(set(d[key]), {"value", "error", "kind"})
            self.assertEqual(d[key]["kind"], "solved")
            self.assertEqual(d[key], getattr(self.r, key).to_dict())
        self.assertTrue(d["precision"]["reached"])
        self.assertNotIn("completed", d)

    def test_density_of_the_finest_grid(self):
        d = stickslip.density(engine="kolmogorov", threads=1)
        self.assertIsInstance(d.stuck_probability, stickslip.GridEstimate)
        self.assertEqual(d.density.shape[0] + 1, d.edges.shape[0])
        mass = float((d.density * (d.edges[1:] - d.edges[:-1])).sum())
        self.assertAlmostEqual(mass + d.stuck_probability.value, 1.0, delta=10 * d.stuck_probability.error)
        self.assertIn("engine='kolmogorov'", repr(d))

    def test_sweep_solved_at_every_point(self):
        s = stickslip.sweep(engine="kolmogorov", noise=[3, 5], tau=[0.5], rel_precision=0.01)
        self.assertEqual(s.method, "kolmogorov")
        for name in ("diffusivity", "mobility", "mean_duration", "stuck_probability", "slope"):
            series = getattr(s, name)
            self.assertIsInstance(series, stickslip.GridEstimateSeries)  # the old name of a solved series
            self.assertIsInstance(series, stickslip.EstimateSeries)
            self.assertEqual(series.kind, "solved")
            self.assertTrue(np.isnan(series.stderr).all(), name)
            self.assertEqual(set(series.to_dict()), {"value", "error", "kind"})
            self.assertEqual(series.value.shape, (1, 2))
            self.assertTrue((series.error > 0).all(), name)
        # The point at noise 5, tau 0.5 is the default model's diffusivity(), bit for bit.
        self.assertEqual(s.diffusivity[0, 1].value, self.r.diffusivity.value)
        self.assertEqual(s.mean_duration[0, 1].error, self.r.mean_duration.error)
        cols = s.to_columns()
        self.assertIn("diffusivity_error", cols)
        self.assertNotIn("diffusivity_stderr", cols)
        with self.assertRaisesRegex(ValueError, "engine kolmogorov"):
            stickslip.sweep(noise=[3, 5], tau=[0.5], rel_precision=0.01)

    def test_refused_where_it_cannot_serve(self):
        with self.assertRaisesRegex(ValueError, "--engine inclusion or pdmp"):
            stickslip.correlation(engine="kolmogorov")
        with self.assertRaisesRegex(ValueError, "stickslip analytic"):
            stickslip.diffusivity(stickslip.Params(tau=0), engine="kolmogorov")


if __name__ == "__main__":
    unittest.main()
