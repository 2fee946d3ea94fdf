#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Golden outputs of the `stickslip` command (the refactoring safety net).

    golden.py STICKSLIP_BINARY            # compare every case of cases.txt
    golden.py STICKSLIP_BINARY --update   # rewrite tests/data/golden/ (say why in the commit)
    golden.py STICKSLIP_BINARY --static-equal
        # every case again with --static-friction equal to its friction: the
        # same output, less the settings listing's static-friction line

Each case's stdout is compared byte for byte with its stored file after the
parts that change from run to run are normalised: the JSON "work" blocks (and
"revision", the build's source revision) are removed; in tables the wall time
and thread count of the work line read "<time>" and "<threads>". Standard
library only, so any Python 3 runs it.
"""
import difflib
import os
import re
import shlex
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "data", "golden")


def cases():
    with open(os.path.join(HERE, "cases.txt")) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            name, args = line.split(":", 1)
            yield name.strip(), shlex.split(args)


def normalise(text):
    out, skip_until = [], None
    for line in text.splitlines(keepends=True):
        if skip_until is not None:
            if re.match(skip_until, line):
                skip_until = None
            continue
        m = re.match(r'^(\s*)"work": \{\s*$', line)
        if m:  # a multi-line "work" object: drop it up to its closing brace
            skip_until = "^" + m.group(1) + r"\},?\s*$"
            continue
        if re.match(r'^\s*"(work|revision)": ', line) or line.startswith("# revision: "):
            continue  # the JSON's and the CSV's source revision
        line = re.sub(r"[0-9.e+-]+ s on \d+ threads?", "<time> s on <threads>", line)
        line = re.sub(r"points in [0-9.e+-]+ s", "points in <time> s", line)
        out.append(line)
    # A removed last member leaves a dangling comma before the closing brace.
    return re.sub(r",(\n\s*[}\]])", r"\1", "".join(out))


DEFAULT_FRICTION = "3.84"  # ModelParams' default (the paper's Fig. 2 case)


def with_static_friction(args):
    """args with --static-friction equal to the case's friction."""
    friction = DEFAULT_FRICTION
    for i, a in enumerate(args):
        if a == "--friction" and i + 1 < len(args):
            friction = args[i + 1]
        elif a.startswith("--friction="):
            friction = a.split("=", 1)[1]
    return [*args, "--static-friction", friction]


def without_static_setting(text):
    """text less the settings listing's static-friction line and the command
    line (JSON or CSV), which name the flag."""
    return "".join(line for line in text.splitlines(True)
                   if not re.match(r'^\s*("static-friction": |# #? ?static-friction = |"command": |# command: )', line))


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    binary, update = argv[1], "--update" in argv[2:]
    static_equal = "--static-equal" in argv[2:]
    env = dict(os.environ, LC_ALL="C")
    failed = 0
    for name, args in cases():
        if static_equal:
            args = with_static_friction(args)
        r = subprocess.run([binary, *args, "--quiet"], capture_output=True, text=True, env=env)
        path = os.path.join(DATA, name + ".txt")
        if r.returncode != 0:
            print(f"FAIL {name}: exit {r.returncode}: {r.stderr.strip()}")
            failed += 1
            continue
        got = normalise(r.stdout)
        if static_equal:
            got = without_static_setting(got)
        if update and not static_equal:
            os.makedirs(DATA, exist_ok=True)
            with open(path, "w") as f:
                f.write(got)
            print(f"wrote {name}")
            continue
        try:
            with open(path) as f:
                want = f.read()
            if static_equal:
                want = without_static_setting(want)
        except FileNotFoundError:
            print(f"FAIL {name}: no golden file {path} (run with --update)")
            failed += 1
            continue
        if got != want:
            failed += 1
            diff = "".join(list(difflib.unified_diff(want.splitlines(True), got.splitlines(True), "golden", "now"))[:40])
            print(f"FAIL {name}: output differs from {path}\n{diff}")
        else:
            print(f"ok   {name}")
    if failed:
        print(f"{failed} golden case(s) failed")
        return 1
    print("all golden cases match")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
