#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Runs every command and code block of README.md, docs/guide.md and
ARCHITECTURE.md (and checks their links), so that
the documentation cannot drift from the program (ctest label "docs").

    /usr/bin/python3 tests/docs/run_doc_commands.py --source . --build build
    /usr/bin/python3 tests/docs/run_doc_commands.py --source . --build build --list   # what would run
    ... --only guide.md:120          # the block that starts on line 120 of docs/guide.md (and its set-up)

What runs, and how
------------------
Each document gets a fresh work folder (a temporary directory) that looks
like the repository root: every top-level entry of the source tree is linked
there, and build/ is a real folder whose entries link to the build tree's, so
`build/stickslip`, `bash scripts/figures` and `/usr/bin/python3
examples/quickstart.py` run as written, while whatever a command writes stays
in the work folder. PATH starts with the binary's folder (so `stickslip`
resolves too), PYTHONPATH is build/python, HOME is a folder inside the work
folder. The blocks of a document run in order, in the same folder, so a block
may use a file that an earlier block wrote (`--print-config > run.toml`, then
`--config run.toml`).

Fenced blocks, by their language:

* ```bash / ```sh / ```shell: every line (a trailing backslash continues it;
  blank lines and comment lines are skipped) is one command, run by
  `bash -o pipefail -c`; it must exit 0.
* ```console: the lines that start with "$ " are the commands; the other lines
  are what the command prints. Every shown line must appear in the actual
  output (stdout and stderr together): first with every number replaced by
  "#" and runs of blanks collapsed (the layout, the words and the notes),
  then number by number: every number exactly as shown (the runs are seeded,
  so the same build prints the same digits), except wall times and rates,
  which may differ by a factor of TIMING_FACTOR (20) either way, thread
  counts, and revision hashes. A block shrunk by a --flag directive (or
  marked "numbers unchecked") is compared without its numbers. "..." stands
  for lines left out. --update rewrites the shown lines whose words match
  but numbers differ with what was printed (review the diff).
* ```python: the block is one script, run by this interpreter; it must exit 0.
* any other language (cmake, cpp, toml, json, text): must carry a directive,
  `test: file PATH` (written to PATH in the work folder, for a later command
  to use) or `not run: REASON`. A block without one fails the test.

Directives
----------
An HTML comment on the lines just before a block (blank lines between are
allowed; GitHub does not render it) tells the test what to do with it:

    <!-- not run: REASON -->
        The block is not run. The test counts these and prints each with its
        reason, so that nothing is skipped silently.
    <!-- test: DIRECTIVE; DIRECTIVE; ... -->
        --flag VALUE [--flag2 VALUE2 ...]
            shrink the block: in every command of the block, the value given
            to --flag is replaced by VALUE (the flag must occur in the block)
        replace 'OLD' 'NEW'
            replace the text OLD by NEW in the block (OLD must occur)
        exit N
            every command of the block must exit with status N (a refusal)
        numbers unchecked
            a console block whose words are compared but not its numbers
            (they depend on the machine: a timing table, a benchmark)
        output unchecked
            a console block whose shown output is not compared (it depends
            on the size the test shrank away, or on the machine)
        needs mpirun
            skipped, and counted as such, where no `mpirun` is on PATH
        file PATH
            write the block to PATH (relative to the work folder)
        timeout SECONDS
            per command (default 120)

The summary at the end lists every block that was not run, or skipped, and
why. Relative links of the documents (files and #anchors of Markdown files)
are checked as well.
"""
import argparse
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time

RUN_LANGS = {"bash", "sh", "shell", "console", "python"}
DEFAULT_TIMEOUT = 120.0
DEFAULT_DOCS = ["README.md", "docs/guide.md", "ARCHITECTURE.md"]

FENCE = re.compile(r"^(\s*)(`{3,}|~{3,})\s*([A-Za-z0-9_+-]*)")
DIRECTIVE = re.compile(r"^\s*<!--\s*(test|not run)\s*:\s*(.*?)\s*-->\s*$")
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


class DocError(Exception):
    pass


class Block:
    def __init__(self, doc, line, lang, text, directives, not_run):
        self.doc, self.line, self.lang, self.text = doc, line, lang, text
        self.directives = directives  # list of strings
        self.not_run = not_run        # reason or None
        self.where = f"{doc}:{line}"


def parse_blocks(path, name):
    """The fenced blocks of a Markdown file, with the directives before each."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    blocks = []
    pending, pending_not_run, pending_line = [], None, None
    i = 0
    while i < len(lines):
        line = lines[i]
        m = DIRECTIVE.match(line)
        if m:
            kind, body = m.group(1), m.group(2)
            if kind == "not run":
                if not body:
                    raise DocError(f"{name}:{i + 1}: 'not run:' needs a reason")
                pending_not_run = body
            else:
                pending += [d.strip() for d in body.split(";") if d.strip()]
            pending_line = i + 1
            i += 1
            continue
        f = FENCE.match(line)
        if f:
            indent, fence, lang = f.group(1), f.group(2), f.group(3).lower()
            body, j = [], i + 1
            while j < len(lines) and not re.match(r"^\s*" + re.escape(fence[0]) + "{" + str(len(fence)) + r",}\s*$",
                                                    lines[j]):
                body.append(lines[j][len(indent):] if lines[j].startswith(indent) else lines[j])
                j += 1
            if j == len(lines):
                raise DocError(f"{name}:{i + 1}: unclosed code fence")
            blocks.append(Block(name, i + 1, lang, "\n".join(body), pending, pending_not_run))
            pending, pending_not_run, pending_line = [], None, None
            i = j + 1
            continue
        if line.strip() and (pending or pending_not_run):
            raise DocError(f"{name}:{pending_line}: a directive must come right before a code block")
        i += 1
    if pending or pending_not_run:
        raise DocError(f"{name}:{pending_line}: a directive at the end, with no code block after it")
    return blocks


def apply_directives(block):
    """(text, options) with the shrinking directives applied."""
    text = block.text
    opts = {"exit": 0, "check_output": True, "needs": [], "file": None, "timeout": DEFAULT_TIMEOUT,
            "exact_numbers": True}
    for d in block.directives:
        if d.startswith("--"):
            toks = shlex.split(d)
            if len(toks) % 2:
                raise DocError(f"{block.where}: '{d}': flags and values must come in pairs")
            opts["exact_numbers"] = False  # a shrunk run prints other numbers than the one shown
            for flag, value in zip(toks[0::2], toks[1::2]):
                pat = re.compile(r"(?<![\w-])(" + re.escape(flag) + r")(=|\s+)(\S+)")
                text, n = pat.subn(lambda m, v=value: m.group(1) + m.group(2) + v, text)
                if n == 0:
                    raise DocError(f"{block.where}: directive {flag} {value}: no {flag} in the block")
        elif d.startswith("replace "):
            toks = shlex.split(d[len("replace "):])
            if len(toks) != 2:
                raise DocError(f"{block.where}: '{d}': replace takes 'OLD' 'NEW'")
            if toks[0] not in text:
                raise DocError(f"{block.where}: replace: {toks[0]!r} is not in the block")
            text = text.replace(toks[0], toks[1])
        elif re.fullmatch(r"exit \d+", d):
            opts["exit"] = int(d.split()[1])
        elif d == "numbers unchecked":
            opts["exact_numbers"] = False
        elif d == "output unchecked":
            opts["check_output"] = False
        elif d.startswith("needs "):
            opts["needs"].append(d[len("needs "):].strip())
        elif d.startswith("file "):
            opts["file"] = d[len("file "):].strip()
        elif re.fullmatch(r"timeout \d+(\.\d*)?", d):
            opts["timeout"] = float(d.split()[1])
        else:
            raise DocError(f"{block.where}: unknown directive '{d}'")
    return text, opts


def shell_commands(text):
    """The commands of a bash/sh block: one per logical line."""
    cmds, cur = [], ""
    for raw in text.split("\n"):
        line = raw.rstrip()
        if not cur and (not line.strip() or line.lstrip().startswith("#")):
            continue
        if line.endswith("\\"):
            cur += line[:-1] + " "
            continue
        cur += line
        cmds.append((cur.strip(), []))
        cur = ""
    if cur:
        cmds.append((cur.strip(), []))
    return cmds


def console_commands(text):
    """(command, shown output lines) of a console block."""
    cmds = []
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("$ "):
            cmd = line[2:]
            while cmd.rstrip().endswith("\\") and i + 1 < len(lines):
                i += 1
                cmd = cmd.rstrip()[:-1] + " " + lines[i].strip()
            cmds.append((cmd.strip(), []))
        elif cmds:
            cmds[-1][1].append(line)
        elif line.strip():
            raise DocError(f"console block: output before the first '$ ' command: {line!r}")
        i += 1
    return cmds


def normalise(line):
    s = NUMBER.sub("#", line)
    s = re.sub(r"\bthreads\b", "thread", s)  # "1 thread" or "2 threads": the machine's core count
    s = re.sub(r"\[\s+", "[", s)  # an interval's padding follows its numbers' widths
    return " ".join(s.split())


# Numbers that depend on the machine, not on the program: compared within
# TIMING_FACTOR (a wall time, a rate), or not at all (a thread count, a
# revision hash). Every other number must be printed exactly as shown.
TIMING_FACTOR = 20.0
MACHINE_NUMBER = [
    re.compile(r"^\s*threads?\b"),                      # "2 threads": the machine's cores
]
TIMING_AFTER = re.compile(r"^\s*(?:s|ms|min|h)\b(?:\s+on\b|\)|,|\s+left|\s*$|\s+\(|\s+elapsed)")
TIMING_KEY = re.compile(r'"(?:seconds|threads|threads_from|revision|version)"\s*:')
HEXISH = re.compile(r"\b(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}\b")


def number_spans(line):
    return [(m.start(), m.end(), m.group(0)) for m in NUMBER.finditer(line)]


def numbers_agree(shown, actual):
    """Whether two lines with the same normalised form print the same numbers,
    timings within TIMING_FACTOR and machine-dependent counts aside."""
    if HEXISH.search(shown) or TIMING_KEY.search(shown):
        shown, actual = HEXISH.sub("h", shown), HEXISH.sub("h", actual)
        if TIMING_KEY.search(shown):
            return True
    a, b = number_spans(shown), number_spans(actual)
    if len(a) != len(b):
        return False
    for (s0, s1, x), (_, _, y) in zip(a, b):
        if x == y:
            continue
        rest = shown[s1:]
        if any(p.search(rest) for p in MACHINE_NUMBER):
            continue
        if TIMING_AFTER.search(rest):
            try:
                fx, fy = float(x), float(y)
            except ValueError:
                return False
            if fx > 0 and fy > 0 and 1 / TIMING_FACTOR <= fy / fx <= TIMING_FACTOR:
                continue
            if fx == fy == 0:
                continue
        return False
    return True


def missing_lines(shown, actual, exact_numbers=True):
    """Shown lines that do not appear in the actual output: compared with
    every number replaced (the words, the layout and the notes), then, with
    exact_numbers, number by number (numbers_agree)."""
    have = {}
    for l in actual.split("\n"):
        have.setdefault(normalise(l), []).append(l)
    out = []
    for l in shown:
        n = normalise(l)
        if not n or n == "...":
            continue
        if n not in have or (exact_numbers and not any(numbers_agree(l, a) for a in have[n])):
            out.append(l)
    return out


def updated_lines(shown, actual):
    """The shown lines with each replaced by the actual line of the same
    normalised form (for --update): the first not yet used, in order."""
    pool = {}
    for l in actual.split("\n"):
        pool.setdefault(normalise(l), []).append(l)
    out = []
    for l in shown:
        n = normalise(l)
        if n and n != "..." and pool.get(n):
            out.append(pool[n].pop(0))
        else:
            out.append(l)
    return out


def write_updates(path, updates):
    """Replaces, within each block's lines of the file, the first remaining
    occurrence of each old shown line by the new one."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    done = set()
    for b, old, new in updates:
        end = b.line + len(b.text.split("\n"))
        for i in range(b.line, min(end + 1, len(lines))):
            if i not in done and lines[i].strip() == old.strip() and lines[i].endswith(old.rstrip()):
                indent = lines[i][: len(lines[i]) - len(lines[i].lstrip())] if not old.startswith(" ") else ""
                lines[i] = indent + new
                done.add(i)
                break
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))


def github_anchor(heading):
    s = heading.strip().lower()
    s = re.sub(r"[`*_]", "", s)
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def check_links(source, name):
    """Relative links of a Markdown file: the file must exist, a #anchor must be a heading of it."""
    path = os.path.join(source, name)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    text_wo_code = re.sub(r"```.*?```", "", text, flags=re.S)
    errors = []
    for m in re.finditer(r"\]\(([^)\s]+)\)", text_wo_code):
        target = m.group(1)
        if re.match(r"^[a-z]+:", target) or target.startswith("mailto:"):
            continue
        file_part, _, anchor = target.partition("#")
        tpath = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
        if not os.path.exists(tpath):
            errors.append(f"{name}: link to {target}: no such file")
            continue
        if anchor and tpath.endswith(".md"):
            with open(tpath, encoding="utf-8") as f:
                body = re.sub(r"```.*?```", "", f.read(), flags=re.S)
            anchors = {github_anchor(h) for h in re.findall(r"^#+\s+(.*)$", body, flags=re.M)}
            if anchor not in anchors:
                errors.append(f"{name}: link to {target}: no heading with anchor #{anchor}")
    return errors


def make_workdir(source, build, tmp):
    """A folder that looks like the repository root (links), with a private build/."""
    for entry in sorted(os.listdir(source)):
        if entry in (".git",) or entry.startswith("build"):
            continue
        os.symlink(os.path.join(source, entry), os.path.join(tmp, entry))
    bdir = os.path.join(tmp, "build")
    os.mkdir(bdir)
    for entry in sorted(os.listdir(build)):
        os.symlink(os.path.join(build, entry), os.path.join(bdir, entry))
    home = os.path.join(tmp, ".home")
    os.mkdir(home)
    return home


def run_env(args, home):
    env = dict(os.environ)
    bindir = os.path.dirname(os.path.abspath(args.bin))
    path = [bindir]
    if args.cmake:
        path.append(os.path.dirname(os.path.abspath(args.cmake)))
    env["PATH"] = os.pathsep.join(path + [env.get("PATH", "")])
    env["PYTHONPATH"] = os.path.join(os.path.abspath(args.build), "python")
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    env["HOME"] = home
    env["MPLBACKEND"] = "Agg"
    env["STICKSLIP_BIN"] = os.path.abspath(args.bin)
    # Open MPI: allow root (CI runs as root), stay on loopback/shared memory.
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    env.setdefault("OMPI_MCA_btl", "self,vader")
    env.setdefault("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
    return env


def run_command(argv, cwd, env, timeout):
    """(exit status or "timeout", stdout + stderr). The command runs in its own
    process group, killed whole on a timeout, with SIGINT at its default (a
    test started in the background of a shell would otherwise pass SIGINT on
    ignored, and a documented Ctrl-C would not stop the command)."""
    def child():
        signal.signal(signal.SIGINT, signal.SIG_DFL)
    p = subprocess.Popen(argv, cwd=cwd, env=env, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, start_new_session=True, preexec_fn=child)
    try:
        out, err = p.communicate(timeout=timeout)
        return p.returncode, out + err
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, err = p.communicate()
        return "timeout", (out or "") + (err or "")


def tail(s, n=40):
    lines = s.rstrip("\n").split("\n")
    return "\n".join(("    " + l) for l in lines[-n:])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--source", required=True, help="the repository root")
    ap.add_argument("--build", required=True, help="the build tree")
    ap.add_argument("--bin", help="the stickslip command (default: BUILD/stickslip)")
    ap.add_argument("--cmake", help="the cmake the commands use (default: the first on PATH)")
    ap.add_argument("--list", action="store_true", help="list the blocks and what would be done, run nothing")
    ap.add_argument("--only", help="DOC:LINE: run only that block (and the file blocks before it)")
    ap.add_argument("--keep", action="store_true", help="keep the work folders")
    ap.add_argument("--update", action="store_true",
                    help="rewrite the shown output of console blocks whose words match but numbers differ "
                         "with what the program printed (regenerates stale examples; review the diff)")
    ap.add_argument("docs", nargs="*", help=f"Markdown files relative to --source (default: {' '.join(DEFAULT_DOCS)})")
    args = ap.parse_args()
    args.source = os.path.abspath(args.source)
    args.build = os.path.abspath(args.build)
    args.bin = args.bin or os.path.join(args.build, "stickslip")
    if not os.access(args.bin, os.X_OK):
        print(f"run_doc_commands: no stickslip command at {args.bin}", file=sys.stderr)
        return 2
    docs = args.docs or DEFAULT_DOCS
    have_mpirun = shutil.which("mpirun") is not None
    have_module = any(n.startswith("_core") for n in os.listdir(os.path.join(args.build, "python", "stickslip"))) \
        if os.path.isdir(os.path.join(args.build, "python", "stickslip")) else False

    failures, not_run, skipped = [], [], []
    counts = {"blocks": 0, "commands": 0, "python": 0, "files": 0}
    start = time.monotonic()
    for name in docs:
        updates = []  # (block, old line, new line) for --update
        try:
            blocks = parse_blocks(os.path.join(args.source, name), name)
        except DocError as e:
            failures.append(str(e))
            continue
        failures += check_links(args.source, name)
        tmp = tempfile.mkdtemp(prefix="stickslip-docs-")
        try:
            home = make_workdir(args.source, args.build, tmp)
            env = run_env(args, home)
            for b in blocks:
                counts["blocks"] += 1
                if b.not_run is not None:
                    not_run.append(f"{b.where} [{b.lang or 'text'}]: {b.not_run}")
                    if args.list:
                        print(f"{b.where} [{b.lang}] not run: {b.not_run}")
                    continue
                try:
                    text, opts = apply_directives(b)
                except DocError as e:
                    failures.append(str(e))
                    continue
                if opts["file"]:
                    dest = os.path.join(tmp, opts["file"])
                    os.makedirs(os.path.dirname(dest), exist_ok=True)
                    with open(dest, "w", encoding="utf-8") as f:
                        f.write(text + "\n")
                    counts["files"] += 1
                    if args.list:
                        print(f"{b.where} [{b.lang}] written to {opts['file']}")
                    continue
                if b.lang not in RUN_LANGS:
                    failures.append(f"{b.where}: a ```{b.lang or '(no language)'} block with no directive: "
                                    "mark it <!-- not run: why --> or <!-- test: file PATH -->")
                    continue
                if args.only and args.only != f"{b.doc}:{b.line}" and not b.where.endswith(args.only):
                    continue
                why_skip = None
                if "mpirun" in opts["needs"] and not have_mpirun:
                    why_skip = "needs mpirun, and there is none on PATH"
                for need in opts["needs"]:
                    if need not in ("mpirun",):
                        failures.append(f"{b.where}: unknown 'needs {need}'")
                uses_python = b.lang == "python" or "python3" in text
                if uses_python and not have_module:
                    why_skip = "needs the Python module, and this build has none (STICKSLIP_PYTHON=OFF)"
                if why_skip:
                    skipped.append(f"{b.where} [{b.lang}]: {why_skip}")
                    continue
                if b.lang == "python":
                    if args.list:
                        print(f"{b.where} [python] script of {len(text.splitlines())} lines")
                        continue
                    script = os.path.join(tmp, f".block-{b.line}.py")
                    with open(script, "w", encoding="utf-8") as f:
                        f.write(text + "\n")
                    t0 = time.monotonic()
                    rc, out = run_command([sys.executable, script], tmp, env, opts["timeout"])
                    dt = time.monotonic() - t0
                    counts["python"] += 1
                    if rc != 0:
                        failures.append(f"{b.where}: python block exited {rc}\n{tail(out)}")
                        print(f"FAIL {b.where} [python] exit {rc} ({dt:.1f} s)")
                    else:
                        print(f"ok   {b.where} [python] ({dt:.1f} s)")
                    continue
                try:
                    cmds = console_commands(text) if b.lang == "console" else shell_commands(text)
                except DocError as e:
                    failures.append(f"{b.where}: {e}")
                    continue
                if not cmds:
                    failures.append(f"{b.where}: a ```{b.lang} block with no command")
                for cmd, shown in cmds:
                    if args.list:
                        print(f"{b.where} [{b.lang}] $ {cmd}" + (f"   (exit {opts['exit']})" if opts["exit"] else ""))
                        continue
                    t0 = time.monotonic()
                    rc, out = run_command(["bash", "-o", "pipefail", "-c", cmd], tmp, env, opts["timeout"])
                    dt = time.monotonic() - t0
                    counts["commands"] += 1
                    bad = None
                    if rc != opts["exit"]:
                        bad = f"exit {rc}, expected {opts['exit']}"
                    elif b.lang == "console" and opts["check_output"]:
                        miss = missing_lines(shown, out, exact_numbers=opts["exact_numbers"])
                        if miss and args.update and opts["exact_numbers"]:
                            for old, new in zip(shown, updated_lines(shown, out)):
                                if old != new:
                                    updates.append((b, old, new))
                            miss = missing_lines(updated_lines(shown, out), out)
                        if miss:
                            bad = "shown output not printed:\n" + "\n".join("      " + l for l in miss)
                    if bad:
                        failures.append(f"{b.where}: $ {cmd}\n  {bad}\n  --- actual output (tail):\n{tail(out)}")
                        print(f"FAIL {b.where} $ {cmd}  ({dt:.1f} s): {bad.splitlines()[0]}")
                    else:
                        print(f"ok   {b.where} $ {cmd}  ({dt:.1f} s)")
            if updates:
                write_updates(os.path.join(args.source, name), updates)
                print(f"updated {len(updates)} shown line(s) in {name}")
        finally:
            if args.keep:
                print(f"work folder of {name}: {tmp}")
            else:
                shutil.rmtree(tmp, ignore_errors=True)

    total = time.monotonic() - start
    print()
    print(f"{counts['blocks']} code blocks in {', '.join(docs)}: {counts['commands']} commands and "
          f"{counts['python']} Python blocks run, {counts['files']} written as files, "
          f"{len(not_run)} not run, {len(skipped)} skipped; {total:.1f} s")
    for n in not_run:
        print(f"  not run  {n}")
    for s in skipped:
        print(f"  skipped  {s}")
    if failures:
        print(f"\n{len(failures)} failure(s):")
        for f in failures:
            print(f"- {f}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
