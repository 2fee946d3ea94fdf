#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Turns the `[measured]` lines printed by the statistical tests (ctest -L
statistical -V) into the markdown table of docs/validation.md, section 1."""
import re
import sys

pat = re.compile(r"\[measured\] (.*?): (\S+) vs (\S+), difference (\S+), combined stderr (\S+), z = (\S+) "
                 r"\(allowed \|diff\| <= (\S+) se \+ (\S+)\)")
test_pat = re.compile(r"\[ RUN      \] (\S+)")
rows, current = [], {}
for line in open(sys.argv[1]):
    # With ctest -V -j, each line starts with its test's number: key on it.
    prefix = re.match(r"^(\d+): ", line)
    key = prefix.group(1) if prefix else ""
    m = test_pat.search(line)
    if m:
        current[key] = m.group(1)
    m = pat.search(line)
    if m:
        what, a, b, diff, se, z, k, allow = m.groups()
        rows.append((current.get(key, "?"), what, float(a), float(b), float(se), float(z), float(k), float(allow)))
print("| test | comparison | estimate | reference | combined stderr | z | tolerance |")
print("|---|---|---|---|---|---|---|")
for test, what, a, b, se, z, k, allow in sorted(rows):
    tol = f"{k:g} se" + (f" + {allow:.3g}" if allow > 0 else "")
    print(f"| `{test}` | {what} | {a:.5g} | {b:.5g} | {se:.3g} | {z:+.2f} | {tol} |")
