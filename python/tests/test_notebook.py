# SPDX-License-Identifier: BSD-3-Clause
"""examples/quickstart.ipynb runs from top to bottom without an error, and is
kept in git without outputs.

The notebook is executed with nbclient in a Python 3 kernel (ipykernel) that
inherits this process's environment, so PYTHONPATH (the build tree's python/
folder, set by ctest) makes `import stickslip` work in it. Skipped, with the
reason, when nbformat, nbclient or ipykernel is missing (Debian:
python3-nbformat, python3-nbclient, python3-ipykernel; scripts/install-deps.sh
installs them).
"""
import os
import tempfile
import time
import unittest

import _support  # noqa: F401  (imports stickslip: the module must be importable)

NOTEBOOK = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                                         "quickstart.ipynb"))


def _missing():
    missing = []
    for name in ("nbformat", "nbclient", "ipykernel", "matplotlib"):
        try:
            __import__(name)
        except ImportError:
            missing.append(name)
    return missing


class QuickstartNotebookTest(unittest.TestCase):
    def test_outputs_are_stripped(self):
        try:
            import nbformat
        except ImportError:
            raise unittest.SkipTest("no nbformat (Debian: python3-nbformat)")
        nb = nbformat.read(NOTEBOOK, as_version=4)
        nbformat.validate(nb)
        for k, cell in enumerate(nb.cells):
            if cell.cell_type == "code":
                self.assertEqual(cell.get("outputs"), [], f"cell {k} has stored outputs: strip them")
                self.assertIsNone(cell.get("execution_count"), f"cell {k} has an execution count: strip it")

    def test_runs(self):
        missing = _missing()
        if missing:
            raise unittest.SkipTest(f"the notebook needs {', '.join(missing)} "
                                    "(Debian: python3-nbclient python3-ipykernel python3-matplotlib)")
        import nbclient
        import nbformat
        nb = nbformat.read(NOTEBOOK, as_version=4)
        env_backend = os.environ.get("MPLBACKEND")
        os.environ["MPLBACKEND"] = "Agg"  # the kernel inherits it; the notebook also selects Agg itself
        os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # ipykernel's debugger: no frozen-module warning
        try:
            with tempfile.TemporaryDirectory() as tmp:
                client = nbclient.NotebookClient(nb, timeout=120, kernel_name="python3",
                                                 resources={"metadata": {"path": tmp}})
                start = time.monotonic()
                client.execute()
                seconds = time.monotonic() - start
        finally:
            if env_backend is None:
                os.environ.pop("MPLBACKEND", None)
            else:
                os.environ["MPLBACKEND"] = env_backend
        images = 0
        for cell in nb.cells:
            if cell.cell_type != "code":
                continue
            for out in cell.get("outputs", []):
                self.assertNotEqual(out.get("output_type"), "error", "".join(out.get("traceback", [])))
                if "image/png" in out.get("data", {}):
                    images += 1
        self.assertEqual(images, 3, "one figure per comparison")
        print(f"\nquickstart.ipynb ran in {seconds:.1f} s")


if __name__ == "__main__":
    unittest.main()
