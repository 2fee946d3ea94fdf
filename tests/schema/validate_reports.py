#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Every JSON report of the CLI against schema/report.schema.json.

Usage: validate_reports.py SCHEMA STICKSLIP_BIN GOLDEN_DIR

(a) runs every subcommand under every engine and scheme it allows (white and
    coloured noise; kolmogorov for diffusivity, density and sweep; analytic's
    closed forms, Fokker-Planck solution and drift-law quadrature; the options
    that add blocks: --rel-precision, --check-dt, --check-knots, the control
    variate on and off, moments --density, trajectory --paths, sweep --vary;
    a run stopped by SIGTERM), each small, in a temporary folder, and
    validates its stdout;
(b) validates every GOLDEN_DIR/*_json.txt;
(c) checks that the validator catches a break of the contract: "error"
    renamed "stderr", a bare number for analytic's diffusivity, an unknown
    top-level key, the retired histogram "stuck" and bins' "density", a
    top-level "method" in a kolmogorov report;
(d) checks that a script written for one engine's JSON reads every other's:
    the same paths exist in diffusivity, density and sweep reports of every
    engine.

One line per report: `name: ok`, or the first error with its JSON path.
Exits 1 on any failure. Needs Debian's python3-jsonschema (4.10 or later).
"""

import copy
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

import jsonschema
from jsonschema import Draft202012Validator

# name: arguments (without --format json --quiet). Small: the whole list runs
# in well under a minute on 2 cores.
COMMANDS = [
    # diffusivity: every engine and scheme, white and coloured noise
    ("diffusivity_resolvent", ["diffusivity", "--scheme", "resolvent", "--excursions", "200", "--dt", "1e-3"]),
    ("diffusivity_event", ["diffusivity", "--scheme", "event", "--excursions", "200", "--dt", "2e-2"]),
    ("diffusivity_pdmp", ["diffusivity", "--engine", "pdmp", "--excursions", "200"]),
    ("diffusivity_kolmogorov", ["diffusivity", "--engine", "kolmogorov", "--rel-precision", "0.01"]),
    ("diffusivity_white_resolvent", ["diffusivity", "--tau", "0", "--scheme", "resolvent", "--excursions", "200", "--dt", "1e-2"]),
    ("diffusivity_white_event", ["diffusivity", "--tau", "0", "--scheme", "event", "--excursions", "200", "--dt", "1e-2"]),
    ("diffusivity_rel_precision", ["diffusivity", "--scheme", "resolvent", "--excursions", "64", "--dt", "1e-3",
                                   "--rel-precision", "0.2", "--max-excursions", "1000"]),
    ("diffusivity_check_dt", ["diffusivity", "--scheme", "resolvent", "--excursions", "200", "--dt", "2e-3", "--check-dt"]),
    ("diffusivity_no_control_variate", ["diffusivity", "--scheme", "resolvent", "--excursions", "200", "--dt", "1e-3",
                                        "--control-variate", "off"]),
    ("diffusivity_paper_estimator", ["diffusivity", "--scheme", "resolvent", "--excursions", "200", "--dt", "1e-3",
                                     "--estimator", "paper"]),
    ("diffusivity_drift_check_knots", ["diffusivity", "--drift", "-v/0.067 + 0.342", "--excursions", "200", "--dt", "1e-3",
                                       "--check-knots"]),
    ("diffusivity_drift_kolmogorov", ["diffusivity", "--drift", "-v/0.067 + 0.342", "--engine", "kolmogorov",
                                      "--rel-precision", "0.01"]),
    # bruteforce
    ("bruteforce_resolvent", ["bruteforce", "--scheme", "resolvent", "--time", "1", "--trajectories", "100", "--dt", "1e-3"]),
    ("bruteforce_event", ["bruteforce", "--scheme", "event", "--time", "1", "--trajectories", "100", "--dt", "2e-2"]),
    ("bruteforce_pdmp", ["bruteforce", "--engine", "pdmp", "--time", "1", "--trajectories", "100"]),
    ("bruteforce_white", ["bruteforce", "--tau", "0", "--time", "1", "--trajectories", "100", "--dt", "1e-2"]),
    # density
    ("density_resolvent", ["density", "--scheme", "resolvent", "--excursions", "100", "--dt", "1e-3", "--bins", "6"]),
    ("density_event", ["density", "--scheme", "event", "--excursions", "100", "--dt", "2e-2", "--bins", "6"]),
    ("density_pdmp", ["density", "--engine", "pdmp", "--excursions", "100", "--bins", "6", "--sample-dt", "1e-3"]),
    ("density_kolmogorov", ["density", "--engine", "kolmogorov"]),
    ("density_white", ["density", "--tau", "0", "--excursions", "100", "--dt", "1e-2", "--bins", "6"]),
    # correlation
    ("correlation_resolvent", ["correlation", "--scheme", "resolvent", "--excursions", "100", "--dt", "1e-3", "--lags", "4",
                               "--max-lag", "0.3"]),
    ("correlation_event", ["correlation", "--scheme", "event", "--excursions", "100", "--dt", "2e-2", "--lags", "4",
                           "--max-lag", "0.3"]),
    ("correlation_pdmp", ["correlation", "--engine", "pdmp", "--excursions", "100", "--lags", "4", "--max-lag", "0.2",
                          "--sample-dt", "1e-3"]),
    ("correlation_white", ["correlation", "--tau", "0", "--excursions", "100", "--dt", "1e-2", "--lags", "4"]),
    # moments
    ("moments_resolvent", ["moments", "--scheme", "resolvent", "--trajectories", "100", "--dt", "1e-3", "--times", "0.05,0.2"]),
    ("moments_event", ["moments", "--scheme", "event", "--trajectories", "100", "--dt", "2e-2", "--times", "0.05,0.2"]),
    ("moments_pdmp", ["moments", "--engine", "pdmp", "--trajectories", "100", "--times", "0,0.1"]),
    ("moments_white", ["moments", "--tau", "0", "--trajectories", "100", "--dt", "1e-2", "--times", "0.05,0.2"]),
    ("moments_density", ["moments", "--trajectories", "100", "--dt", "1e-3", "--times", "0.05,0.2", "--density", "--bins", "6"]),
    # trajectory: one long excursion, and --paths
    ("trajectory_resolvent", ["trajectory", "--scheme", "resolvent", "--dt", "1e-2", "--every", "0.5"]),
    ("trajectory_event", ["trajectory", "--scheme", "event", "--dt", "5e-2", "--every", "0.5"]),
    ("trajectory_pdmp", ["trajectory", "--engine", "pdmp", "--every", "0.5"]),
    ("trajectory_white", ["trajectory", "--tau", "0", "--dt", "1e-2", "--every", "0.5"]),
    ("trajectory_paths_resolvent", ["trajectory", "--scheme", "resolvent", "--paths", "2", "--time", "0.5", "--every", "0.1",
                                    "--dt", "1e-3"]),
    ("trajectory_paths_event", ["trajectory", "--scheme", "event", "--paths", "2", "--time", "0.5", "--every", "0.1",
                                "--dt", "2e-2"]),
    ("trajectory_paths_pdmp", ["trajectory", "--engine", "pdmp", "--paths", "2", "--time", "0.5", "--every", "0.1"]),
    ("trajectory_paths_white", ["trajectory", "--tau", "0", "--paths", "2", "--time", "0.5", "--every", "0.1", "--dt", "1e-2"]),
    # sweep
    ("sweep_resolvent", ["sweep", "--scheme", "resolvent", "--noise", "2,4", "--tau", "0.25,0.5", "--excursions", "64",
                         "--dt", "1e-3"]),
    ("sweep_event", ["sweep", "--scheme", "event", "--noise", "2,4", "--tau", "0.5", "--excursions", "64", "--dt", "2e-2"]),
    ("sweep_pdmp", ["sweep", "--engine", "pdmp", "--noise", "2,4", "--tau", "0.5", "--excursions", "64"]),
    ("sweep_auto_dt_white", ["sweep", "--noise", "2,4", "--tau", "0,0.5", "--excursions", "64"]),
    ("sweep_kolmogorov", ["sweep", "--engine", "kolmogorov", "--noise", "1,2", "--tau", "0.5", "--rel-precision", "0.01"]),
    ("sweep_kolmogorov_white_limits", ["sweep", "--engine", "kolmogorov", "--noise", "5", "--tau", "0.03,0.06",
                                       "--rel-precision", "0.05"]),
    ("sweep_vary", ["sweep", "--scheme", "resolvent", "--drift", "-v/0.067 + c", "--vary", "c", "--vary-values", "0.2,0.342",
                    "--noise", "2,4", "--tau", "0.5", "--excursions", "64", "--dt", "1e-3"]),
    ("sweep_vary_kolmogorov", ["sweep", "--engine", "kolmogorov", "--drift", "-v/0.067 + c", "--vary", "c",
                               "--vary-values", "0.2,0.342", "--noise", "2,4", "--tau", "0.5", "--rel-precision", "0.05"]),
    # analytic: affine law (closed forms), with --times and --velocities
    # (closed forms for pure dry friction, Fokker-Planck otherwise), a drift law
    # (quadrature)
    ("analytic", ["analytic"]),
    ("analytic_times_fokker_planck", ["analytic", "--times", "0.1,1", "--velocities=-1,0,1"]),
    ("analytic_times_closed_form", ["analytic", "--friction", "1", "--noise", "1", "--relaxation", "inf", "--bias", "0",
                                    "--v0", "1", "--times", "0.1,1", "--velocities=-1,0,1"]),
    ("analytic_drift", ["analytic", "--drift", "-v + 0.3 - 0.1*v^3"]),
    ("analytic_drift_velocities", ["analytic", "--drift", "-v + 0.3 - 0.1*v^3", "--velocities=-1,0,1"]),
    # spectrum: the kolmogorov engine (the chain on the Fig. 2 case), the
    # white-noise closed form
    ("spectrum_kolmogorov", ["spectrum", "--frequencies", "0,1", "--rel-precision", "0.01"]),
    ("spectrum_closed_form", ["spectrum", "--tau", "0", "--relaxation", "inf", "--bias", "0.3", "--frequencies", "0,1"]),
    ("spectrum_fokker_planck", ["spectrum", "--tau", "0", "--frequencies", "0,1"]),
    ("spectrum_sampled_event", ["spectrum", "--engine", "inclusion", "--excursions", "64", "--frequencies", "0,1"]),
    ("spectrum_sampled_white", ["spectrum", "--engine", "inclusion", "--tau", "0", "--dt", "1e-3", "--excursions", "16",
                                "--frequencies", "1"]),
    ("spectrum_sampled_pdmp", ["spectrum", "--engine", "pdmp", "--excursions", "16", "--sample-dt", "0.01",
                               "--frequencies", "0.5"]),
]

# Runs stopped by SIGTERM after a moment: the result so far, marked
# "interrupted". The first two are stopped after a block has finished; the
# third at once, before any excursion completed, where the CLI writes the
# report of a run with no estimate (src/report/interrupted.cpp). A signal that
# lands before the CLI's handler is installed leaves no output: then that
# case is skipped, not failed.
INTERRUPTED = [
    ("diffusivity_interrupted", ["diffusivity", "--scheme", "event", "--dt", "1e-4", "--excursions", "100000",
                                 "--threads", "1"], 1.0),
    ("diffusivity_kolmogorov_interrupted", ["diffusivity", "--engine", "kolmogorov", "--rel-precision", "1e-5"], 0.5),
    ("diffusivity_interrupted_at_once", ["diffusivity", "--excursions", "100000", "--threads", "1"], 0.01),
]

# (d): paths every engine's report must have, per subcommand.
READS_ACROSS = {
    "diffusivity": (["diffusivity_resolvent", "diffusivity_event", "diffusivity_pdmp", "diffusivity_kolmogorov"],
                    ["diffusivity.value", "diffusivity.error", "diffusivity.kind", "mobility.value", "mobility.error",
                     "mobility.kind", "mean_duration.value", "mean_duration.error"]),
    "density": (["density_resolvent", "density_event", "density_pdmp", "density_kolmogorov", "density_white"],
                ["stuck_probability.value", "stuck_probability.error", "histogram.bins[0].lo", "histogram.bins[0].hi",
                 "histogram.bins[0].value", "histogram.bins[0].error", "histogram.bins[0].kind", "mean.value",
                 "mean.error", "variance.value", "diffusivity.value"]),
    "sweep": (["sweep_resolvent", "sweep_event", "sweep_pdmp", "sweep_kolmogorov"],
              ["points[0].diffusivity.value", "points[0].diffusivity.error", "points[0].diffusivity.kind",
               "points[0].slope.value", "points[0].slope.error", "points[0].white_ratio.value",
               "points[0].mean_duration.value", "exponents[0].exponent.value", "exponents[0].exponent.error"]),
}


def lookup(report, path):
    """The value at a path like 'points[0].slope.value', or raise KeyError/IndexError/TypeError."""
    node = report
    for part in path.split("."):
        name, _, rest = part.partition("[")
        node = node[name]
        while rest:
            index, _, rest = rest.partition("]")
            node = node[int(index)]
            rest = rest.lstrip("[")
    return node


def kind_of(instance):
    return instance.get("kind") if isinstance(instance, dict) else None


def first_error(validator, instance):
    """The most useful error: the first by position in the document, and for a
    oneOf/anyOf of estimates, the error of the branch the instance's "kind"
    selects (not "is not valid under any of the given schemas")."""
    errors = sorted(validator.iter_errors(instance), key=lambda e: [str(p) for p in e.absolute_path])
    if not errors:
        return None
    error = errors[0]
    while error.context:
        branches = {}
        for sub in error.context:
            branches.setdefault(sub.schema_path[0] if sub.schema_path else 0, []).append(sub)
        # Drop the branches that fail on "kind" itself: the instance's kind
        # is not theirs.
        wanted = [subs for subs in branches.values()
                  if not any(s.validator == "const" and list(s.relative_path)[-1:] == ["kind"] for s in subs)]
        if len(wanted) != 1:
            error = jsonschema.exceptions.best_match(error.context)
            break
        error = sorted(wanted[0], key=lambda e: len(e.relative_path))[0]
        if not error.context:
            break
    return error


def describe(error):
    where = error.json_path if hasattr(error, "json_path") else "$" + "".join(
        f"[{p}]" if isinstance(p, int) else f".{p}" for p in error.absolute_path)
    message = error.message
    if len(message) > 300:
        message = message[:300] + "..."
    return f"{where}: {message}"


class Checker:
    def __init__(self, validator):
        self.validator = validator
        self.failures = 0
        self.reports = {}

    def line(self, name, ok, text="ok"):
        print(f"{name}: {text}", flush=True)
        if not ok:
            self.failures += 1

    def validate(self, name, report):
        error = first_error(self.validator, report)
        if error is None:
            self.line(name, True)
            return True
        self.line(name, False, "FAIL " + describe(error))
        return False

    def rejects(self, name, report, why):
        """(c): the validator must reject this broken report."""
        error = first_error(self.validator, report)
        if error is None:
            self.line(f"self-test {name}", False, f"FAIL the schema accepts {why}")
        else:
            self.line(f"self-test {name}", True, f"ok (rejected: {describe(error)})")


def run(binary, args, workdir, stop_after=None):
    command = [binary] + args + ["--format", "json", "--quiet"]
    if stop_after is None:
        done = subprocess.run(command, cwd=workdir, capture_output=True, text=True, timeout=120)
        return done.returncode, done.stdout, done.stderr
    process = subprocess.Popen(command, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(stop_after)
    process.send_signal(signal.SIGTERM)
    out, err = process.communicate(timeout=60)
    return process.returncode, out, err


def main(argv):
    if len(argv) != 4:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    schema_path, binary, golden_dir = argv[1:]
    with open(schema_path, encoding="utf-8") as f:
        schema = json.load(f)
    Draft202012Validator.check_schema(schema)
    checker = Checker(Draft202012Validator(schema))
    binary = os.path.abspath(binary)
    started = time.monotonic()

    # (a) every subcommand x engine x scheme the CLI allows
    with tempfile.TemporaryDirectory(prefix="stickslip-schema-") as workdir:
        for name, args, stop_after in [(n, a, None) for n, a in COMMANDS] + INTERRUPTED:
            rc, out, err = run(binary, args, workdir, stop_after)
            expected = (0,) if stop_after is None else (0, 128 + signal.SIGTERM)
            if stop_after is not None and rc in (-signal.SIGTERM, 128 + signal.SIGTERM) and not out.strip():
                print(f"{name}: skipped (the signal came before the CLI could catch it)", flush=True)
                continue
            if rc not in expected:
                checker.line(name, False, f"FAIL exit {rc}: {err.strip()[:300]}")
                continue
            try:
                report = json.loads(out)
            except ValueError as e:
                checker.line(name, False, f"FAIL not JSON ({e}): {out[:200]!r}")
                continue
            if stop_after is not None and report.get("interrupted") is not True:
                # The run finished before the signal: still a report to check.
                name += " (finished before the signal)"
            checker.reports[name] = report
            checker.validate(name, report)

    # (b) the golden files
    goldens = sorted(f for f in os.listdir(golden_dir) if f.endswith("_json.txt"))
    if not goldens:
        checker.line("golden", False, f"FAIL no *_json.txt in {golden_dir}")
    for f in goldens:
        with open(os.path.join(golden_dir, f), encoding="utf-8") as handle:
            try:
                report = json.load(handle)
            except ValueError as e:
                checker.line(f"golden {f}", False, f"FAIL not JSON ({e})")
                continue
        checker.validate(f"golden {f}", report)

    # (c) the validator catches a break of the contract
    base = checker.reports.get("diffusivity_resolvent")
    analytic = checker.reports.get("analytic")
    kolmogorov = checker.reports.get("diffusivity_kolmogorov")
    density = checker.reports.get("density_resolvent")
    if not (base and analytic and kolmogorov and density):
        checker.line("self-test", False, "FAIL a report it needs did not run")
    else:
        broken = copy.deepcopy(base)
        broken["diffusivity"]["stderr"] = broken["diffusivity"].pop("error")
        checker.rejects("stderr", broken, '"stderr" for "error" in diffusivity')
        # The same estimate against $defs/estimate alone (without the rule
        # that bans "stderr" everywhere): the estimate's own keys catch it.
        estimate_only = Draft202012Validator({"$schema": schema.get("$schema"), "$defs": schema["$defs"],
                                              "$ref": "#/$defs/estimate"})
        error = first_error(estimate_only, broken["diffusivity"])
        checker.line("self-test stderr_in_estimate", error is not None,
                     f"ok (rejected: {describe(error)})" if error else
                     'FAIL $defs/estimate accepts "stderr" for "error"')
        broken = copy.deepcopy(analytic)
        broken["diffusivity"] = broken["diffusivity"]["value"]
        checker.rejects("bare_number", broken, "a bare number for analytic's diffusivity")
        broken = copy.deepcopy(base)
        broken["diffusivity_estimate"] = broken["diffusivity"]
        checker.rejects("unknown_key", broken, "an unknown top-level key")
        broken = copy.deepcopy(kolmogorov)
        broken["method"] = broken["engine_details"].pop("method")
        checker.rejects("kolmogorov_method", broken, 'a top-level "method" in a kolmogorov report')
        broken = copy.deepcopy(density)
        broken["histogram"]["stuck"] = broken["stuck_probability"]
        checker.rejects("histogram_stuck", broken, 'the retired "histogram.stuck"')
        broken = copy.deepcopy(density)
        broken["histogram"]["bins"][0]["density"] = broken["histogram"]["bins"][0].pop("value")
        checker.rejects("bin_density", broken, 'a bin\'s retired "density" key')
        broken = copy.deepcopy(base)
        broken["settings"]["stderr"] = 1
        checker.rejects("stderr_anywhere", broken, '"stderr" in a free-form block')
        broken = copy.deepcopy(base)
        broken["mobility"]["kind"] = "solved"
        checker.rejects("solved_with_ci", broken, "a solved estimate with an interval")

    # (d) a script written for one engine's JSON reads every other's
    for subcommand, (names, paths) in READS_ACROSS.items():
        for name in names:
            report = checker.reports.get(name)
            if report is None:
                checker.line(f"reads {name}", False, "FAIL the report did not run")
                continue
            missing = []
            for path in paths:
                try:
                    lookup(report, path)
                except (KeyError, IndexError, TypeError):
                    missing.append(path)
            if missing:
                checker.line(f"reads {name}", False, "FAIL missing " + ", ".join(missing))
            else:
                checker.line(f"reads {name}", True, f"ok ({len(paths)} {subcommand} paths)")

    seconds = time.monotonic() - started
    if checker.failures:
        print(f"{checker.failures} failure(s) ({seconds:.1f} s)")
        return 1
    print(f"all reports match {schema_path} ({seconds:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
