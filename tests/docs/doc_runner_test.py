#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""The doc test must fail on a changed number (ctest docs.runner_catches_a_changed_number).

    /usr/bin/python3 tests/docs/doc_runner_test.py BUILD_DIR STICKSLIP

Writes three one-block documents around `stickslip analytic` (exact
references: the same digits on every machine) and runs run_doc_commands.py on
each: the output as printed passes; one digit changed fails, naming the line;
the same change in a block marked "numbers unchecked" passes.
"""
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def run(build, binary, text):
    with tempfile.TemporaryDirectory(prefix="stickslip-doc-runner-") as src:
        with open(os.path.join(src, "doc.md"), "w", encoding="utf-8") as f:
            f.write(text)
        p = subprocess.run([sys.executable, os.path.join(HERE, "run_doc_commands.py"), "--source", src, "--build",
                            build, "--bin", binary, "doc.md"], capture_output=True, text=True)
        return p.returncode, p.stdout + p.stderr


def main():
    build, binary = sys.argv[1], sys.argv[2]
    line = next(l for l in subprocess.run([binary, "analytic"], capture_output=True, text=True, check=True)
                .stdout.split("\n") if l.startswith("diffusivity D"))
    digits = [i for i, c in enumerate(line) if c.isdigit()]
    changed = line[:digits[3]] + str((int(line[digits[3]]) + 1) % 10) + line[digits[3] + 1:]
    block = "```console\n$ stickslip analytic\n{}\n```\n"
    failures = []
    rc, out = run(build, binary, block.format(line))
    if rc != 0:
        failures.append(f"the printed line itself failed (exit {rc}):\n{out}")
    rc, out = run(build, binary, block.format(changed))
    if rc == 0 or changed not in out:
        failures.append(f"a changed digit passed (exit {rc}); shown: {changed!r}\n{out}")
    rc, out = run(build, binary, "<!-- test: numbers unchecked -->\n" + block.format(changed))
    if rc != 0:
        failures.append(f"'numbers unchecked' still compared the numbers (exit {rc}):\n{out}")
    for f in failures:
        print("FAIL", f)
    print("doc runner: the printed line passes, a changed digit fails, 'numbers unchecked' ignores it"
          if not failures else f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
