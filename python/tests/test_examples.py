# SPDX-License-Identifier: BSD-3-Clause
"""examples/quickstart.py runs (smoke size) and writes its PNG."""
import os
import subprocess
import sys
import tempfile
import unittest

EXAMPLE = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                                        "quickstart.py"))


class QuickstartTest(unittest.TestCase):
    def test_smoke(self):
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            raise unittest.SkipTest("no matplotlib (Debian: python3-matplotlib)")
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "q.png")
            p = subprocess.run([sys.executable, EXAMPLE, "--out", out, "--excursions", "64", "--threads", "2"],
                               capture_output=True, text=True, timeout=120, cwd=tmp)
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertIn("wrote", p.stdout)
            with open(out, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")


if __name__ == "__main__":
    unittest.main()
