#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""The pip install from the sdist, as a user does it offline on Debian (ctest
packaging.pip_sdist, label pip; docs/guide.md#installation-with-pip):

    /usr/bin/python3 tests/packaging/pip_sdist_test.py --source . --work /tmp/pip-test

1. `setup.py sdist` makes stickslip-<version>.tar.gz from the source tree; the
   archive must hold every file git tracks (but .ci/) and the REVISION file.
2. A fresh virtual environment made by /usr/bin/python3 with
   --system-site-packages (Debian's numpy, setuptools, wheel, pybind11-dev's
   CMake package) installs the archive with
   `pip install --no-build-isolation --no-index`: a full CMake build of the
   library, the Python module and the command from the unpacked archive alone.
3. From the environment: the console script `stickslip` and
   `python -m stickslip` print the version and revision, run a small
   diffusivity job, and refuse bad input with exit status 2 (so the wrapper
   passes the command's status through); `import stickslip` comes from the
   environment, and stickslip.diffusivity gives the command's numbers.

CMAKE_ARGS and CMAKE_BUILD_PARALLEL_LEVEL in the environment reach the build
(setup.py); the test builds with 2 jobs unless told otherwise.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import time
from pathlib import Path


def run(cmd, **kw):
    print("+", " ".join(str(c) for c in cmd), flush=True)
    return subprocess.run([str(c) for c in cmd], **kw)


def check(cmd, **kw):
    r = run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        sys.exit(f"FAIL: exit {r.returncode}\n{r.stdout}\n{r.stderr}")
    return r.stdout


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--source", required=True, help="the source tree")
    ap.add_argument("--work", required=True, help="scratch folder (emptied first)")
    ap.add_argument("--python", default="/usr/bin/python3", help="interpreter that makes the venv")
    ap.add_argument("--expected-version", help="the CMake project's VERSION")
    a = ap.parse_args()
    source = Path(a.source).resolve()
    work = Path(a.work).resolve()
    shutil.rmtree(work, ignore_errors=True)
    (work / "dist").mkdir(parents=True)
    t0 = time.monotonic()

    # 1. The sdist.
    check([a.python, "setup.py", "-q", "sdist", "--dist-dir", work / "dist"], cwd=source)
    archives = list((work / "dist").glob("stickslip-*.tar.gz"))
    if len(archives) != 1:
        sys.exit(f"FAIL: expected one stickslip-*.tar.gz in {work / 'dist'}, found {archives}")
    archive = archives[0]
    version = archive.name[len("stickslip-"):-len(".tar.gz")]
    if a.expected_version and version != a.expected_version:
        sys.exit(f"FAIL: the sdist is version {version}, the project {a.expected_version}")
    top = f"stickslip-{version}/"
    with tarfile.open(archive) as tar:
        held = {m.name[len(top):] for m in tar.getmembers() if m.isfile() and m.name.startswith(top)}
        revision = tar.extractfile(top + "REVISION").read().decode().strip() if "REVISION" in held else None
    if revision is None:
        sys.exit("FAIL: the sdist has no REVISION file")
    git = shutil.which("git")
    if git and (source / ".git").exists():
        tracked = subprocess.run([git, "ls-files"], cwd=source, capture_output=True, text=True,
                                 check=True).stdout.split("\n")
        missing = sorted(f for f in tracked if f and not f.startswith(".ci/") and f not in held)
        if missing:
            sys.exit(f"FAIL: {len(missing)} tracked files are not in the sdist: {missing[:20]}")
        if not revision:
            sys.exit("FAIL: the sdist of a git checkout has an empty REVISION")
        print(f"sdist: {archive.name}, {len(held)} files, every tracked file but .ci/, revision {revision}")
    else:
        print(f"sdist: {archive.name}, {len(held)} files (not a git checkout: contents not compared)")

    # 2. A fresh venv, the offline install.
    venv = work / "venv"
    check([a.python, "-m", "venv", "--system-site-packages", venv])
    py = venv / "bin" / "python"
    env = dict(os.environ)
    env.setdefault("CMAKE_BUILD_PARALLEL_LEVEL", "2")
    env.pop("PYTHONPATH", None)  # the build tree's module must not stand in for the installed one
    env.pop("STICKSLIP_CLI", None)
    env.pop("STICKSLIP_CMAKE_BUILD_DIR", None)
    # With ccache on PATH a rerun compiles nothing: TMPDIR and CCACHE_BASEDIR
    # make pip's randomly named unpack folder a relative path for ccache. (An
    # unoptimised build was tried: 20% less CPU time, not worth testing a build
    # that users do not get.)
    if "CMAKE_ARGS" not in env and shutil.which("ccache"):
        (work / "tmp").mkdir()
        env["CMAKE_ARGS"] = "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"
        env["TMPDIR"] = env["CCACHE_BASEDIR"] = str(work / "tmp")
    print(f"CMAKE_ARGS={env.get('CMAKE_ARGS', '')}")
    t1 = time.monotonic()
    # --no-cache-dir: never a wheel that pip cached from an earlier archive of
    # the same name and version. A stickslip in the system site (scripts/build.sh
    # puts one there) does not count: pip installs into the venv all the same,
    # and takes numpy from the system site.
    r = run([py, "-m", "pip", "install", "--no-build-isolation", "--no-index", "--no-cache-dir", archive],
            env=env, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: pip install exited {r.returncode}\n{r.stdout[-4000:]}\n{r.stderr[-8000:]}")
    print(f"pip install from the sdist: {time.monotonic() - t1:.0f} s")
    # The declared dependency (numpy) is met; Debian's own packages may have
    # unmet requirements of their own, which are not ours to check.
    deps = run([py, "-m", "pip", "check"], env=env, capture_output=True, text=True).stdout
    if any(line.lower().startswith("stickslip ") for line in deps.split("\n")):
        sys.exit(f"FAIL: pip check:\n{deps}")

    # 3. The command and the module, from the venv (run from the work folder,
    # not the source tree, so that ./python/stickslip cannot be imported).
    stickslip = venv / "bin" / "stickslip"
    if not stickslip.is_file():
        sys.exit(f"FAIL: pip installed no console script {stickslip}")
    where = check([py, "-c", "import stickslip, stickslip.__main__ as m; print(stickslip.__file__); "
                   "print(m.command_path())"], env=env, cwd=work).split("\n")
    for path in where[:2]:
        if not path.startswith(str(venv)):
            sys.exit(f"FAIL: {path} is not inside the venv {venv}")
    expected_version = f"stickslip {version}" + (f" (git {revision})" if revision else "")
    for cmd in ([stickslip], [py, "-m", "stickslip"]):
        out = check([*cmd, "--version"], env=env, cwd=work)
        if not out.startswith(expected_version):
            sys.exit(f"FAIL: {cmd} --version printed {out!r}, expected {expected_version!r}...")
        bad = run([*cmd, "diffusivity", "--excursions", "1"], env=env, cwd=work, capture_output=True, text=True)
        if bad.returncode != 2 or "--excursions" not in bad.stderr:
            sys.exit(f"FAIL: {cmd} with bad input: exit {bad.returncode} (expected 2), stderr {bad.stderr!r}")
    flags = ["--excursions", "300", "--seed", "7", "--dt", "0.005"]
    cli = json.loads(check([stickslip, "diffusivity", *flags, "--format", "json"], env=env, cwd=work))
    via_m = json.loads(check([py, "-m", "stickslip", "diffusivity", *flags, "--format", "json"], env=env, cwd=work))
    py_out = json.loads(check([py, "-c", "import json, stickslip; "
                               "r = stickslip.diffusivity(excursions=300, seed=7, dt=0.005); "
                               "print(json.dumps(r.to_dict()))"], env=env, cwd=work))
    for name, got in (("python -m stickslip", via_m), ("stickslip.diffusivity", py_out)):
        if got["diffusivity"] != cli["diffusivity"]:
            sys.exit(f"FAIL: {name} gave D = {got['diffusivity']}, the command {cli['diffusivity']}")
    d = cli["diffusivity"]
    value = d["value"] if isinstance(d, dict) else d
    if not (isinstance(value, float) and 0 < value < 1):
        sys.exit(f"FAIL: implausible D {d}")
    print(f"command, python -m stickslip and stickslip.diffusivity agree: D = {value} m^2/s")
    print(f"pip sdist test passed in {time.monotonic() - t0:.0f} s")


if __name__ == "__main__":
    main()
