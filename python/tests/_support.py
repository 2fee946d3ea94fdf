# SPDX-License-Identifier: BSD-3-Clause
"""Shared helpers of the Python tests (unittest; pytest runs them too).

The tests import the module from PYTHONPATH (ctest sets it to the build tree's
python/ folder) and find the `stickslip` command from STICKSLIP_CLI (set by
ctest), else build/stickslip next to the source tree. Tests that need the
command are skipped when there is none.
"""
import json
import os
import subprocess
import unittest

import stickslip  # noqa: F401  (fails loudly here if the module is not importable)

_HERE = os.path.dirname(os.path.abspath(__file__))


def cli_path():
    env = os.environ.get("STICKSLIP_CLI")
    if env and os.access(env, os.X_OK):
        return env
    guess = os.path.normpath(os.path.join(_HERE, "..", "..", "build", "stickslip"))
    return guess if os.access(guess, os.X_OK) else None


def run_cli(*args):
    """(returncode, stdout, stderr) of the `stickslip` command."""
    exe = cli_path()
    if exe is None:
        raise unittest.SkipTest("no stickslip command (set STICKSLIP_CLI)")
    p = subprocess.run([exe, *args, "--quiet"] if args and args[0] != "--version" else [exe, *args],
                       capture_output=True, text=True, timeout=120)
    return p.returncode, p.stdout, p.stderr


def cli_json(*args):
    rc, out, err = run_cli(*args, "--format", "json")
    if rc != 0:
        raise AssertionError(f"stickslip {' '.join(args)} failed ({rc}): {err}")
    return json.loads(out)


def cli_error(*args):
    """The CLI's one-line error, without its 'stickslip: error: ' prefix."""
    rc, out, err = run_cli(*args)
    if rc != 2:
        raise AssertionError(f"stickslip {' '.join(args)}: expected exit code 2, got {rc}: {err}")
    line = err.strip()
    prefix = "stickslip: error: "
    assert line.startswith(prefix), line
    return line[len(prefix):]


def without_work(d):
    """A CLI/to_dict() JSON object without its timing parts ("work", also per
    sweep point) and what says how the run was asked for rather than what it
    computed: the command (a command line, a Python call) and the thread count."""
    d = dict(d)
    d.pop("work", None)
    d.pop("revision", None)
    d.pop("command", None)
    if "settings" in d:
        d["settings"] = {k: v for k, v in d["settings"].items() if k != "threads"}
    if "points" in d and isinstance(d["points"], list):
        d["points"] = [{k: v for k, v in p.items() if k != "work"} for p in d["points"]]
    return d
