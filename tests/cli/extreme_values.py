#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Every subcommand with extreme finite values of every numeric flag.

Issue "Nothing lost, nothing silently wrong", item 3: no NaN, inf or null may
leave the program as a result with exit 0. For each subcommand, each numeric
flag its --help lists (workload, seed and thread counts aside: their extremes
are long runs, not wrong numbers) is set, one at a time, to each of
+-1e308, 1e15 and 5e-324, on a small base run. Each run must end
with exit 2 (refused up front) or 3 (untrustworthy), or with exit 0 and a JSON
result whose numbers outside "params" are all finite. A run that takes longer
than the timeout fails too, and the failure lists every offending command.

Usage: extreme_values.py STICKSLIP [--timeout SECONDS]
"""
import json
import math
import re
import subprocess
import sys

exe = sys.argv[1]
timeout = float(sys.argv[sys.argv.index("--timeout") + 1]) if "--timeout" in sys.argv else 20.0

base = {
    "diffusivity": ["--excursions", "200"],
    "bruteforce": ["--trajectories", "50", "--time", "1"],
    "density": ["--excursions", "200"],
    "moments": ["--trajectories", "50"],
    "correlation": ["--excursions", "200"],
    "trajectory": [],
    "analytic": [],
    "sweep": ["--excursions", "200", "--noise", "4,5", "--tau", "0.5"],
    # Monte Carlo: each kolmogorov solve takes seconds, too long for 4 values of every flag.
    "spectrum": ["--engine", "inclusion", "--excursions", "200", "--frequencies", "0,1"],
}
skip = {"excursions", "trajectories", "paths", "max-steps", "threads", "seed", "checkpoint-every", "bins", "index",
        "max-excursions", "rel-precision-max"}
values = ["1e308", "-1e308", "1e15", "5e-324"]
# Runs that would start and run for hours instead of being refused or given a
# predicted duration: none since the run-duration predictor (issue item 5);
# the set stays so that no new one joins silently.
known_slow = set()
# Settings that are parameters, not results: a null there means "not applicable".
inputs = {"params", "nondimensional", "work", "settings"}
# A sweep's fits are null where too few points define them (check_finite_result
# in the library makes the same exception; the points' D and M0 are checked).
fits = {"slope", "exponents"}


def numeric_flags(cmd):
    text = subprocess.run([exe, cmd, "--help"], capture_output=True, text=True, check=True).stdout
    flags = re.findall(r"^\s+--([a-z0-9-]+) (?:NUM|INT|LIST|NUM\|inf|NUM\|auto|SECONDS)", text, re.M)
    return [f for f in flags if f not in skip]


def first_bad(node, path=""):
    """The first null or non-finite number outside the inputs, as a JSON path."""
    if isinstance(node, dict):
        for k, v in node.items():
            if (path == "" and k in inputs) or k in fits:
                continue
            bad = first_bad(v, f"{path}.{k}")
            if bad:
                return bad
    elif isinstance(node, list):
        for i, v in enumerate(node):
            bad = first_bad(v, f"{path}[{i}]")
            if bad:
                return bad
    elif node is None or (isinstance(node, float) and not math.isfinite(node)):
        return path or "."
    return None


failures, runs = [], 0
for cmd, extra in base.items():
    for flag in numeric_flags(cmd):
        for value in values:
            if (cmd, flag, value) in known_slow:
                continue
            argv = [exe, cmd] + extra + [f"--{flag}={value}", "--format", "json", "--quiet", "--threads", "2"]
            if (cmd, flag) in (("sweep", "noise"), ("sweep", "tau"), ("spectrum", "frequencies")):
                # a list flag given twice would add up
                i = argv.index(f"--{flag}")
                del argv[i:i + 2]
            runs += 1
            shown = " ".join(argv[1:])
            try:
                r = subprocess.run(argv, capture_output=True, text=True, timeout=timeout)
            except subprocess.TimeoutExpired:
                failures.append(f"still running after {timeout:g} s: {shown}")
                continue
            if r.returncode in (2, 3):
                if r.stdout.strip():
                    failures.append(f"exit {r.returncode} but printed a result: {shown}")
                continue
            if r.returncode != 0:
                failures.append(f"exit {r.returncode}: {shown}: {r.stderr.strip()[:200]}")
                continue
            try:
                # nlohmann writes NaN and inf as null; Python's parser reads NaN/Infinity too.
                bad = first_bad(json.loads(r.stdout))
            except ValueError as e:
                failures.append(f"exit 0 with output that is not JSON ({e}): {shown}")
                continue
            if bad:
                failures.append(f"exit 0 with a non-finite result at {bad}: {shown}")
print(f"{runs} runs, {len(failures)} failures")
for f in failures:
    print("  " + f)
sys.exit(1 if failures else 0)
