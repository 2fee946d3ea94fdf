# SPDX-License-Identifier: BSD-3-Clause
"""Every output says what produced it (the JSON's command and settings, the
CSV's '#' lines, Python's meta, the .npz files), and the Python conventions:
notes as StickslipWarning naming keywords, tables (to_columns, to_dataframe),
sweep arrays shaped (n_tau, n_noise), integer arguments, the progress line."""
import contextlib
import io
import json
import os
import tempfile
import unittest
import warnings

import numpy as np

import stickslip
from _support import run_cli

RUNS = [  # small runs of several commands, each a few tenths of a second
    ["diffusivity", "--scheme", "resolvent", "--excursions", "256", "--dt", "1e-3", "--seed", "12345678901234567890"],
    ["density", "--engine", "pdmp", "--excursions", "128", "--bins", "6", "--range=-1,1"],
    ["sweep", "--noise", "4:6:3", "--tau", "0.5", "--excursions", "64"],
    ["moments", "--scheme", "resolvent", "--trajectories", "100", "--dt", "1e-3", "--times", "0.1,0.5"],
    ["analytic", "--bias", "0.2", "--times", "0.1,1", "--v0", "0.5"],
]


def csv_parts(text):
    """(the '#' lines, the rest) of a CSV report."""
    lines = text.splitlines(keepends=True)
    head = [ln for ln in lines if ln.startswith("#")]
    return head, "".join(lines[len(head):])


def without_work(j):
    """The JSON less its timing: every "work" member (a sweep's points have one each)."""
    if isinstance(j, dict):
        return {k: without_work(v) for k, v in j.items() if k != "work"}
    if isinstance(j, list):
        return [without_work(v) for v in j]
    return j


def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, int) and v > 2**63 - 1:
        return json.dumps(str(v))  # TOML's integers are 64-bit signed: a larger seed is quoted
    return repr(v)


class CliProvenance(unittest.TestCase):
    def cli(self, *args):
        rc, out, err = run_cli(*args)
        self.assertEqual(rc, 0, err)
        return out

    def test_json_has_command_and_every_setting(self):
        args = RUNS[0]
        d = json.loads(self.cli(*args, "--format", "json"))
        self.assertEqual(d["command"], "stickslip " + " ".join(args) + " --format json --quiet")
        config = self.cli(*args, "--print-config")
        keys = [ln.split(" = ")[0].lstrip("# ") for ln in config.splitlines() if " = " in ln]
        self.assertEqual(list(d["settings"]), keys)  # every setting, in --print-config's order
        self.assertEqual(d["settings"]["seed"], 12345678901234567890)  # exactly: not through a double
        self.assertEqual(d["settings"]["excursions"], 256)
        self.assertIsNone(d["settings"]["x0"] if "x0" in d["settings"] else None)

    def test_the_command_is_quoted_as_a_shell_would_need(self):
        d = json.loads(self.cli("analytic", "--drift", "0.342 - v/0.067", "--format", "json"))
        self.assertEqual(d["command"], "stickslip analytic --drift '0.342 - v/0.067' --format json --quiet")
        self.assertEqual(d["settings"]["drift"], "0.342 - v/0.067")

    def test_csv_header_is_a_config_that_reproduces_the_run(self):
        with tempfile.TemporaryDirectory() as tmp:
            for args in RUNS:
                with self.subTest(command=args[0]):
                    head, body = csv_parts(self.cli(*args, "--format", "csv"))
                    self.assertTrue(head[0].startswith(f"# stickslip {args[0]}, version {stickslip.__version__}"))
                    self.assertIn("# command: stickslip " + " ".join(args) + " --format csv --quiet\n", head)
                    if args[0] != "analytic":
                        self.assertIn("# seed: 1\n" if "--seed" not in args else "# seed: 12345678901234567890\n",
                                      head)
                    start = head.index(next(h for h in head if h.startswith("# settings:"))) + 1
                    path = os.path.join(tmp, args[0] + ".toml")
                    with open(path, "w") as f:
                        f.write("".join(h[2:] for h in head[start:]))
                    _, again = csv_parts(self.cli(args[0], "--config", path, "--format", "csv"))
                    self.assertEqual(again, body)

    def test_json_settings_reproduce_the_run(self):
        with tempfile.TemporaryDirectory() as tmp:
            for args in RUNS:
                with self.subTest(command=args[0]):
                    d = json.loads(self.cli(*args, "--format", "json"))
                    path = os.path.join(tmp, args[0] + ".toml")
                    with open(path, "w") as f:
                        for key, value in d["settings"].items():
                            if value is not None:
                                f.write(f"{key} = {toml_value(value)}\n")
                    again = json.loads(self.cli(args[0], "--config", path, "--format", "json"))
                    for x in (d, again):
                        x.pop("command")
                    self.assertEqual(without_work(again), without_work(d))

    def test_csv_keeps_every_digit(self):
        args = RUNS[0]
        d = json.loads(self.cli(*args, "--format", "json"))
        _, body = csv_parts(self.cli(*args, "--format", "csv"))
        header, row = body.splitlines()[:2]
        cells = dict(zip(header.split(","), row.split(",")))
        self.assertEqual(float(cells["diffusivity"]), d["diffusivity"]["value"])  # the same double, bit for bit
        self.assertEqual(float(cells["diffusivity_error"]), d["diffusivity"]["error"])
        self.assertEqual(float(cells["mobility_lo"]), d["mobility"]["ci"][0])


def small(**kw):
    base = dict(excursions=256, scheme="resolvent", dt=1e-3)
    base.update(kw)
    return base


class PythonProvenance(unittest.TestCase):
    def setUp(self):
        warnings.simplefilter("ignore", stickslip.StickslipWarning)
        self.addCleanup(warnings.resetwarnings)

    def test_meta_is_the_json_provenance(self):
        r = stickslip.diffusivity(stickslip.Params(), **small(seed=3))
        d = r.to_dict()
        self.assertEqual(r.meta["command"], "stickslip.diffusivity(" + repr(stickslip.Params()) +
                         ", excursions=256, scheme='resolvent', dt=0.001, seed=3)")
        for key in ("command", "settings", "version"):
            self.assertEqual(r.meta[key], d[key])
        self.assertEqual(r.meta["settings"]["seed"], 3)
        head, _ = csv_parts(r.to_csv())
        self.assertIn("# command: " + r.meta["command"] + "\n", head)

    def test_to_npz_and_save(self):
        r = stickslip.correlation(stickslip.Params(), **small(excursions=128, lags=4))
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "c.npz")
            r.save(path)
            z = np.load(path)
            self.assertEqual(json.loads(str(z["meta"])), r.meta)
            np.testing.assert_array_equal(z["lag"], r.lag)
            np.testing.assert_array_equal(z["covariance_error"], r.covariance.stderr)
            for suffix, render in ((".json", r.to_json), (".csv", r.to_csv), (".txt", r.to_table)):
                r.save(os.path.join(tmp, "c" + suffix))
                with open(os.path.join(tmp, "c" + suffix)) as f:
                    self.assertEqual(f.read(), render())
            self.assertEqual(sorted(os.listdir(tmp)), ["c.csv", "c.json", "c.npz", "c.txt"])  # no temporary left
            with self.assertRaises(ValueError):
                r.save(os.path.join(tmp, "c.unknown"))

    def test_columns_of_every_result_type(self):
        p = stickslip.Params()
        runs = {
            "diffusivity": (stickslip.diffusivity(p, **small()), 1),
            "bruteforce": (stickslip.bruteforce(p, scheme="resolvent", dt=1e-3, time=1, trajectories=100), 1),
            "density": (stickslip.density(p, **small(excursions=128, bins=7)), 7),
            "correlation": (stickslip.correlation(p, **small(excursions=128, lags=4)), 5),
            "moments": (stickslip.moments(p, scheme="resolvent", dt=1e-3, trajectories=100, times=[0.1, 0.2, 0.3]), 3),
            "sweep": (stickslip.sweep(p, noise=[4, 5, 6], tau=[0.5, 1], excursions=64), 6),
        }
        t = stickslip.trajectory(p, scheme="resolvent", dt=1e-2, paths=2, time=1, every=0.25)
        runs["trajectory"] = (t, sum(len(x) for x in t.paths))
        for name, (r, rows) in runs.items():
            with self.subTest(result=name):
                cols = r.to_columns()
                self.assertTrue(all(len(c) == rows for c in cols.values()), {k: len(c) for k, c in cols.items()})
                value = {"density": "density", "correlation": "covariance", "moments": "first_moment",
                         "trajectory": "v"}.get(name, "diffusivity")
                self.assertIn(value, cols)
                if name != "trajectory":
                    for suffix in ("_error", "_lo", "_hi"):
                        self.assertIn(value + suffix, cols)
                try:
                    import pandas  # noqa: F401
                except ImportError:
                    with self.assertRaisesRegex(ImportError, "pandas"):
                        r.to_dataframe()
                    continue
                frame = r.to_dataframe()
                self.assertEqual(frame.shape, (rows, len(cols)))
                self.assertEqual(list(frame.columns), list(cols))
                self.assertEqual(frame.attrs["meta"], r.meta)

    @unittest.skipUnless(__import__("importlib").util.find_spec("pandas"), "pandas is not installed")
    def test_dataframe_is_tidy(self):
        r = stickslip.density(stickslip.Params(), **small(excursions=128, bins=5))
        frame = r.to_dataframe()
        self.assertEqual(len(frame), 5)
        np.testing.assert_array_equal(frame["density_error"].to_numpy(), r.density.stderr)

    def test_sweep_arrays_have_the_grid_shape(self):
        r = stickslip.sweep(stickslip.Params(), noise=[4, 5, 6], tau=[0.5, 1], excursions=64)
        self.assertEqual(r.shape, (2, 3))
        for a in (r.diffusivity.value, r.diffusivity.stderr, r.mobility.lo, r.slope.value, r.noise, r.tau):
            self.assertEqual(a.shape, (2, 3))
        self.assertEqual(r.diffusivity.ci.shape, (2, 3, 2))
        np.testing.assert_array_equal(r.tau[:, 0], r.taus)
        np.testing.assert_array_equal(r.noise[0], r.noises)
        points = r.to_dict()["points"]
        self.assertEqual(r.diffusivity[1, 2].value, points[5]["diffusivity"]["value"])  # tau-major

    def test_integers_where_floats_are_taken(self):
        a = stickslip.diffusivity(stickslip.Params(noise=4), **small(dt=1e-3))
        b = stickslip.diffusivity(stickslip.Params(noise=4.0), **small(dt=0.001))
        self.assertEqual(a.diffusivity.value, b.diffusivity.value)
        c = stickslip.diffusivity({"noise": 4, "friction": 4}, **small(level=1 - 0.05))
        self.assertEqual(c.params.friction, 4.0)


class Warnings(unittest.TestCase):
    def test_notes_are_warnings_naming_keywords(self):
        with self.assertWarns(stickslip.StickslipWarning) as caught:
            r = stickslip.diffusivity(stickslip.Params(), **small(control_variate_pilot=0))  # the note on few excursions
        self.assertEqual(caught.filename, __file__)  # attributed to the caller's line
        self.assertIn(str(caught.warning), r.warnings)
        self.assertTrue(r.warnings)
        note = stickslip._core.python_text(
            "raise --max-steps, use a coarser --dt or pass --allow-capped; --tau 0; --checkpoint-every 5; --nope")
        self.assertEqual(note, "raise max_steps, use a coarser dt or pass allow_capped; tau 0; checkpoint_every 5; --nope")

    def test_run_warns_too(self):
        req = stickslip.DiffusivityRequest()
        for k, v in small(control_variate_pilot=0).items():
            req.set(k, v)
        with self.assertWarns(stickslip.StickslipWarning):
            stickslip.run(req)

    def test_the_table_is_every_setting(self):
        table = stickslip.keyword_of_flag
        for request in (stickslip.DiffusivityRequest, stickslip.SweepRequest, stickslip.TrajectoryRequest):
            for s in request.settings():
                self.assertEqual(table[s["flag"]], s["keyword"])
        self.assertEqual(table["--relaxation"], "relaxation")  # the model's: Params' keywords
        for r in (stickslip.diffusivity(stickslip.Params(), **small(max_steps=4000, allow_capped=True,
                                                                     excursions=64)),):
            for w in r.warnings:
                self.assertNotIn("--max-steps", w)


class Progress(unittest.TestCase):
    def test_the_progress_line_ends_with_a_newline(self):
        err = io.StringIO()
        with contextlib.redirect_stderr(err), warnings.catch_warnings():
            warnings.simplefilter("ignore", stickslip.StickslipWarning)
            stickslip.diffusivity(stickslip.Params(), **small(excursions=2000), progress=True)
        text = err.getvalue()
        self.assertTrue(text == "" or text.endswith("\n"), repr(text[-80:]))


if __name__ == "__main__":
    unittest.main()
