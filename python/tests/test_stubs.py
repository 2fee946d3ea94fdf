# SPDX-License-Identifier: BSD-3-Clause
"""The package's type stubs (__init__.pyi) are generated from the request structures
and must be up to date; every keyword function takes exactly its request's settings."""
import inspect
import os
import subprocess
import sys
import unittest

import stickslip

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "make_stubs.py")


class StubsTest(unittest.TestCase):
    def test_stubs_are_up_to_date(self):
        p = subprocess.run([sys.executable, TOOL, "--check"], capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)

    def test_functions_take_their_requests_settings(self):
        for function, request in (("diffusivity", stickslip.DiffusivityRequest), ("sweep", stickslip.SweepRequest),
                                  ("moments", stickslip.MomentsRequest), ("trajectory", stickslip.TrajectoryRequest),
                                  ("density", stickslip.DensityRequest), ("bruteforce", stickslip.BruteForceRequest),
                                  ("correlation", stickslip.CorrelationRequest)):
            sig = inspect.signature(getattr(stickslip, function))
            run_keywords = ("checkpoint", "checkpoint_every", "resume") if request.resumable else ()
            names = [p for p in sig.parameters if p not in ("params", "progress")]
            self.assertEqual(names, [s["keyword"] for s in request.settings()] + list(run_keywords), function)
            doc = getattr(stickslip, function).__doc__
            for s in request.settings():
                self.assertIn(f"    {s['keyword']} : ", doc, function)
                if s["unit"]:
                    self.assertIn(f"[{s['unit']}]", doc, function)


if __name__ == "__main__":
    unittest.main()
