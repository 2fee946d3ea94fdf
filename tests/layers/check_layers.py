#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Holds ARCHITECTURE.md's include rule to the code.

The layers, bottom up: core, model, random and stats, engines, driver,
deterministic, quantities, report. A file includes headers of its own layer
and the layers below, never above. A file under src/ belongs to the layer of
its folder (src/<layer>/...); a public header to the layer ARCHITECTURE.md's
table gives it (a folder entry such as `kernels/` covers what is in it).
Every `#include "..."` that names a file of the tree is checked; a public
header the table does not place is an error too, so the table stays whole.

Usage: check_layers.py SOURCE_DIR. Exit 0 when the rule holds (less the known
exceptions below), 1 with one line per offending include otherwise.
check_layers.py --self-test: the check must fail on a small tree that breaks
the rule (an engine including a driver header, an unplaced public header).
"""
import os
import re
import sys

RANK = {"core": 0, "model": 1, "random": 2, "stats": 2, "engines": 3, "driver": 4,
        "deterministic": 5, "quantities": 6, "report": 7}

# Known includes that go up a layer, (file, include) pairs that ARCHITECTURE.md
# would have to justify: none today, and a new one fails unless listed here; one
# that disappears must leave this list too.
KNOWN = set()

SOURCES = (".hpp", ".cpp", ".h", ".cu", ".cuh")


def table(root):
    """Public header (or folder, with a trailing '/') -> layer, from ARCHITECTURE.md."""
    text = open(os.path.join(root, "ARCHITECTURE.md"), encoding="utf-8").read()
    start = text.index("| layer | `include/stickslip/` |")
    places = {}
    for line in text[start:].splitlines()[2:]:
        if not line.startswith("|"):
            break
        layer_cell, headers = [c.strip() for c in line.strip().strip("|").split("|")]
        layers = [w.strip(",") for w in layer_cell.split() if w.strip(",") in RANK]
        if not layers:
            sys.exit(f"check_layers: ARCHITECTURE.md's layer table names no known layer in {layer_cell!r}")
        for name in re.findall(r"`([^`]+)`", headers):
            # A row may hold two layers of one rank ("random, stats"): the folder's own name decides.
            folder = name.rstrip("/")
            places[name] = folder if folder in layers else layers[0]
    return places


def check(root):
    places = table(root)
    problems = []

    def layer_of(rel):
        if rel.startswith("include/stickslip/"):
            name = rel[len("include/stickslip/"):]
            key = name.split("/")[0] + "/" if "/" in name else name
            if key not in places:
                problems.append(f"{rel}: a public header that ARCHITECTURE.md's layer table does not place")
                return None
            return places[key]
        if rel.startswith("src/"):
            layer = rel.split("/")[1]
            if layer not in RANK:
                problems.append(f"{rel}: src/{layer}/ is not a layer of ARCHITECTURE.md")
                return None
            return layer
        return None

    files = []
    for top in ("include/stickslip", "src"):
        for folder, _, names in os.walk(os.path.join(root, top)):
            files += [os.path.relpath(os.path.join(folder, n), root) for n in names if n.endswith(SOURCES)]
    seen_known = set()
    for rel in sorted(files):
        own = layer_of(rel)
        if own is None:
            continue
        text = open(os.path.join(root, rel), encoding="utf-8").read()
        for inc in re.findall(r'^\s*#\s*include\s+"([^"]+)"', text, re.M):
            target = os.path.join("include", inc) if inc.startswith("stickslip/") else os.path.join("src", inc)
            if not os.path.exists(os.path.join(root, target)):
                continue  # generated (build tree) or not ours
            other = layer_of(target)
            if other is None or RANK[other] <= RANK[own]:
                continue
            if (rel, inc) in KNOWN:
                seen_known.add((rel, inc))
                continue
            problems.append(f"{rel} ({own}) includes {inc} ({other}): up a layer")
    for rel, inc in sorted(KNOWN - seen_known):
        problems.append(f"{rel} no longer includes {inc} up a layer: drop it from KNOWN in {__file__}")
    problems += kernels_behind_the_api(root, places)
    return files, problems


def kernels_behind_the_api(root, places):
    """The API's headers (the quantities row) must not pull in a kernel
    (kernels/), directly or through other headers: a user who includes
    diffusivity.hpp compiles no step of an engine."""
    def includes(rel):
        path = os.path.join(root, "include", rel)
        if not os.path.exists(path):
            return []
        text = open(path, encoding="utf-8").read()
        return [i for i in re.findall(r'^\s*#\s*include\s+"([^"]+)"', text, re.M) if i.startswith("stickslip/")]
    problems = []
    for name, layer in sorted(places.items()):
        if layer != "quantities" or name.endswith("/"):
            continue
        start = "stickslip/" + name
        seen, todo, via = {start}, [start], {start: None}
        while todo:
            here = todo.pop()
            for inc in includes(here):
                if inc not in seen:
                    seen.add(inc)
                    via[inc] = here
                    todo.append(inc)
        for inc in sorted(seen):
            if inc.startswith("stickslip/kernels/"):
                chain, at = [], inc
                while at is not None:
                    chain.append(at)
                    at = via[at]
                problems.append(f"include/{start} pulls in a kernel: {' <- '.join(chain)}")
    return problems


def self_test():
    import tempfile
    with tempfile.TemporaryDirectory() as root:
        def write(rel, text):
            os.makedirs(os.path.dirname(os.path.join(root, rel)), exist_ok=True)
            open(os.path.join(root, rel), "w", encoding="utf-8").write(text)
        write("ARCHITECTURE.md", "| layer | `include/stickslip/` |\n|---|---|\n| engines | `engine.hpp`, `kernels/` |\n"
                                 "| driver (a run) | `run.hpp` |\n| quantities (the API) | `api.hpp` |\n")
        write("include/stickslip/kernels/step.hpp", "#pragma once\n")
        write("include/stickslip/api.hpp", '#include "stickslip/run.hpp"\n')
        write("include/stickslip/engine.hpp", "#pragma once\n")
        write("include/stickslip/run.hpp", '#include "stickslip/engine.hpp"\n#include "stickslip/kernels/step.hpp"\n')
        write("include/stickslip/stray.hpp", "#pragma once\n")
        write("src/engines/adapter.hpp", '#include "stickslip/run.hpp"\n')
        _, problems = check(root)
    wanted = ["src/engines/adapter.hpp (engines) includes stickslip/run.hpp (driver): up a layer",
              "include/stickslip/stray.hpp: a public header that ARCHITECTURE.md's layer table does not place",
              "include/stickslip/api.hpp pulls in a kernel: stickslip/kernels/step.hpp <- stickslip/run.hpp "
              "<- stickslip/api.hpp"]
    missing = [w for w in wanted if w not in problems]
    for w in missing:
        print("check_layers --self-test: not caught:", w)
    print("check_layers --self-test:", "failed" if missing else "the check catches all three")
    return 1 if missing else 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    files, problems = check(root)
    for p in sorted(set(problems)):
        print("check_layers:", p)
    if not problems:
        print(f"check_layers: {len(files)} files keep ARCHITECTURE.md's layers ({len(KNOWN)} known exceptions)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
