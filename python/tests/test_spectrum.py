# SPDX-License-Identifier: BSD-3-Clause
"""stickslip.spectrum under each of its methods: the kolmogorov engine, the
white-noise closed form (no drag), the Fokker-Planck chain (white noise with
drag) and Monte Carlo (engine="inclusion" or "pdmp"). Each result keeps the
same fields; .method says which computed it, and S(0) is its D."""
import math
import unittest

import stickslip

FIG2 = stickslip.Params(friction=3.84, noise=5, tau=0.5, relaxation=0.067, bias=0.342)


class SpectrumMethodsTest(unittest.TestCase):
    def check(self, result, method_prefix, kind):
        self.assertTrue(result.method.startswith(method_prefix), result.method)
        self.assertEqual(list(result.frequency), [0.0, 1.0])
        self.assertEqual(result.spectrum.value[0], result.diffusivity.value)  # S(0) = D
        self.assertGreater(result.spectrum.value[0], result.spectrum.value[1])
        self.assertEqual(result.spectrum.kind, kind)
        self.assertIn("spectrum", result.to_dict())

    def test_every_method(self):
        solved = stickslip.spectrum(FIG2, frequencies=[0, 1], rel_precision=0.05)
        self.check(solved, "kolmogorov", "solved")
        self.assertEqual(solved.excursions, 0)
        closed = stickslip.spectrum(FIG2.replace(tau=0, relaxation=math.inf), frequencies=[0, 1])
        self.check(closed, "closed form", "exact")
        fokker_planck = stickslip.spectrum(FIG2.replace(tau=0), frequencies=[0, 1])
        self.check(fokker_planck, "fokker-planck", "solved")
        sampled = stickslip.spectrum(FIG2, engine="inclusion", excursions=300, frequencies=[0, 1])
        self.check(sampled, "monte carlo", "sampled")
        self.assertEqual(sampled.excursions, 300)
        # The sampled value and the solved one: within 4 of the run's standard errors.
        self.assertLess(abs(sampled.spectrum.value[1] - solved.spectrum.value[1]), 4 * sampled.spectrum.error[1])

    def test_sampling_settings_are_the_monte_carlo_engines(self):
        with self.assertRaises(stickslip.InvalidParameterError) as caught:
            stickslip.spectrum(FIG2, frequencies=[1], seed=3)  # the kolmogorov engine samples nothing
        self.assertEqual(caught.exception.parameter, "seed")


if __name__ == "__main__":
    unittest.main()
