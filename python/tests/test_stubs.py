# SPDX-License-Identifier: BSD-3-Clause
"""The package's type stubs (__init__.pyi, and _core.pyi's classes of results that
declare their fields) and the JSON Schema's blocks of those results are generated
and must be up to date; every keyword function takes exactly its request's settings."""
import inspect
import os
import subprocess
import sys
import unittest

import stickslip

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "make_stubs.py")
SCHEMA_TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "make_schema.py")


class StubsTest(unittest.TestCase):
    def test_stubs_are_up_to_date(self):
        p = subprocess.run([sys.executable, TOOL, "--check"], capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)

    def test_schema_follows_the_declared_fields(self):
        # The JSON Schema's blocks of results that declare their fields (result_fields.hpp).
        p = subprocess.run([sys.executable, SCHEMA_TOOL, "--check"], capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)

    def test_declared_fields_are_documented_properties(self):
        # result_fields.hpp: each declared field of a Python class is a property whose
        # docstring is the declaration's help and unit.
        declared = stickslip._core._result_fields()
        self.assertTrue(any(d["python_class"] == "SweepExponent" for d in declared))
        for d in declared:
            if not d["python_class"] or d["python_class"].startswith("_"):
                continue  # a dict of its JSON block, or flattened into the results (a stub-only base)
            cls = getattr(stickslip._core, d["python_class"])  # every class, exported or not
            for f in d["fields"]:
                prop = getattr(cls, f["name"].replace(".", "_"))
                self.assertIsInstance(prop, property, f["name"])
                self.assertIn(f["help"], prop.__doc__)
                if f["unit"]:
                    self.assertIn(f"[{f['unit']}]", prop.__doc__)

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
