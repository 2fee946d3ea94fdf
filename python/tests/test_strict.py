# SPDX-License-Identifier: BSD-3-Clause
"""Python is as strict as the CLI (issue 50, item 4): what the command refuses
with exit 3 raises UntrustworthyResultError with the result attached, and
the model's keywords are refused where the command refuses its flags."""
import math
import unittest

import stickslip
from stickslip import analytic


class UntrustworthyResultsRaise(unittest.TestCase):
    def check(self, call):
        with self.assertRaises(stickslip.UntrustworthyResultError) as c:
            call()
        self.assertIn("not a finite number", str(c.exception))
        self.assertTrue(hasattr(c.exception, "result"))
        return c.exception.result

    def test_runs(self):
        # Each returned NaN, inf or a negative D without an exception.
        self.check(lambda: stickslip.density(excursions=40, sample_dt=1e3, bins=4))
        self.check(lambda: stickslip.correlation(excursions=40, sample_dt=1e3, lags=2))
        self.check(lambda: stickslip.trajectory(dt=1e308))

    def test_analytic(self):
        result = self.check(lambda: analytic.first_moment(stickslip.Params(), [1e23]))
        self.assertTrue(math.isnan(result[0]))
        self.assertTrue(math.isfinite(analytic.first_moment(stickslip.Params(), [0.5])[0]))

    def test_kolmogorov_beyond_its_grids_is_refused(self):
        with self.assertRaises(stickslip.InvalidParameterError) as c:  # it gave D = -5e-26
            stickslip.diffusivity(stickslip.Params(tau=1e3), engine="kolmogorov", rel_precision=0.01)
        self.assertEqual(c.exception.parameter, "tau")


class ParamsAsStrictAsTheFlags(unittest.TestCase):
    def refused(self, name, **kw):
        with self.assertRaises(stickslip.InvalidParameterError) as c:
            stickslip.Params(**kw)
        self.assertEqual(c.exception.parameter, name, str(c.exception))

    def test_drift_laws(self):
        self.refused("relaxation", drift="-v", relaxation=1)  # the relaxation was dropped
        self.refused("bias", drift="-v", bias=0.1)
        self.refused("drift", drift=([], []))                # the default law ran
        self.refused("drift", drift=5)                       # a bare TypeError
        self.refused("drift", drift=([1, 2], [1, "a"]))      # pybind11's "Unable to cast"
        self.refused("drift-params", drift_params="a=1")
        self.refused("knots", knots=65)
        with self.assertRaises(stickslip.InvalidParameterError):
            stickslip.Params(drift="-v").replace(bias=0.2)
        # Replacing the law by the affine one with its bias is fine.
        p = stickslip.Params(drift="-v").replace(drift=None, bias=0.2)
        self.assertEqual(p.bias, 0.2)


if __name__ == "__main__":
    unittest.main()
