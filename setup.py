# SPDX-License-Identifier: BSD-3-Clause
"""Builds the compiled parts of the Python package with CMake for `pip install`,
`pip wheel` and `setup.py sdist` (the metadata lives in pyproject.toml).

The wheel gets the extension stickslip._core and the `stickslip` command as
stickslip/_bin/stickslip, which the console script `stickslip` and
`python -m stickslip` run (python/stickslip/__main__.py).

By default a fresh CMake build under build-pip/ (setuptools' build_temp) is
configured for the interpreter running pip and only the module and the command
are built: no tests, benchmarks, docs, MPI or CUDA. Environment:

  CMAKE_ARGS="-D..."            extra configure arguments, after ours
                                 (e.g. -DSTICKSLIP_NATIVE=ON, or
                                 -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  CMAKE_BUILD_PARALLEL_LEVEL=N  build jobs (default: all cores)
  STICKSLIP_CMAKE_BUILD_DIR=dir reuse that configured build folder instead (it
                                 must have STICKSLIP_PYTHON=ON for this same
                                 interpreter; scripts/build.sh does this); its
                                 command is bundled when it builds one.

Build requirements: pybind11 and numpy are declared in pyproject.toml; cmake
(>= 3.20) and ninja are added by setup_requires only when none is on PATH, so
that an isolated (networked) build uses the machine's own when it has them.
The C++ libraries (Boost, Eigen, nlohmann-json, muParser, Random123, CLI11, toml++)
and a C++20 compiler come from the system: docs/guide.md#installation-with-pip.
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext
from setuptools.command.sdist import sdist

ROOT = Path(__file__).resolve().parent
BUILD_BASE = "build-pip"  # setuptools' own folders; /build*/ is git-ignored
MODULE_TARGET = "stickslip_python"
CLI_TARGET = "stickslip_cli"
CMAKE_MINIMUM = (3, 20)


def _cmake_version(cmake):
    try:
        out = subprocess.run([cmake, "--version"], capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    m = re.search(r"version (\d+)\.(\d+)", out)
    return (int(m.group(1)), int(m.group(2))) if m else None


def _missing_build_tools():
    """cmake and ninja from PyPI, only where the machine lacks them."""
    needed = []
    cmake = shutil.which("cmake")
    if cmake is None or (_cmake_version(cmake) or (0, 0)) < CMAKE_MINIMUM:
        needed.append("cmake>=%d.%d" % CMAKE_MINIMUM)
    if shutil.which("ninja") is None and shutil.which("make") is None:
        needed.append("ninja")
    return needed


def _cache_value(cache, key):
    m = re.search(rf"^{re.escape(key)}:[A-Z]+=(.*)$", cache, re.M)
    return m.group(1) if m else None


def _revision():
    """The checkout's revision as cmake/source_revision.cmake writes it, or ""."""
    if not (ROOT / ".git").exists():
        return ""
    try:
        rev = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], cwd=ROOT, capture_output=True,
                             text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "diff", "--quiet", "HEAD", "--"], cwd=ROOT).returncode != 0
    except (OSError, subprocess.CalledProcessError):
        return ""
    return rev + ("-dirty" if dirty else "")


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def _configure_fresh(self):
        build_dir = Path(self.build_temp).resolve() / "cmake"
        build_dir.mkdir(parents=True, exist_ok=True)
        args = ["cmake", "-S", str(ROOT), "-B", str(build_dir)]
        if shutil.which("ninja") and not (build_dir / "CMakeCache.txt").exists():
            args += ["-G", "Ninja"]
        args += ["-DCMAKE_BUILD_TYPE=Release", "-DSTICKSLIP_BUILD_TESTS=OFF", "-DSTICKSLIP_BUILD_CLI=ON",
                 "-DSTICKSLIP_PYTHON=ON", "-DSTICKSLIP_BUILD_BENCH=OFF", "-DSTICKSLIP_BUILD_DOCS=OFF",
                 "-DSTICKSLIP_MPI=OFF", "-DSTICKSLIP_CUDA=OFF", f"-DPython3_EXECUTABLE={sys.executable}"]
        try:  # pybind11 from PyPI (isolated builds); Debian's pybind11-dev is found by CMake itself
            import pybind11
            args.append(f"-Dpybind11_DIR={pybind11.get_cmake_dir()}")
        except ImportError:
            pass
        args += shlex.split(os.environ.get("CMAKE_ARGS", ""))
        subprocess.check_call(args)
        return build_dir, [MODULE_TARGET, CLI_TARGET]

    def _reuse(self, reuse):
        build_dir = (ROOT / reuse).resolve() if not os.path.isabs(reuse) else Path(reuse)
        cache_file = build_dir / "CMakeCache.txt"
        if not cache_file.is_file():
            sys.exit(f"stickslip: STICKSLIP_CMAKE_BUILD_DIR={reuse}: no CMakeCache.txt there")
        cache = cache_file.read_text()
        if _cache_value(cache, "STICKSLIP_PYTHON") not in ("ON", "TRUE", "1"):
            sys.exit(f"stickslip: {build_dir} has STICKSLIP_PYTHON off")
        exe = _cache_value(cache, "Python3_EXECUTABLE")
        if exe and os.path.realpath(exe) != os.path.realpath(sys.executable):
            sys.exit(f"stickslip: {build_dir} builds the module for {exe}, not for {sys.executable}")
        targets = [MODULE_TARGET]
        if _cache_value(cache, "STICKSLIP_BUILD_CLI") not in ("OFF", "FALSE", "0"):
            targets.append(CLI_TARGET)
        return build_dir, targets

    def build_extension(self, ext):
        if shutil.which("cmake") is None:
            sys.exit("stickslip: cmake is needed to build the Python module (Debian: cmake)")
        reuse = os.environ.get("STICKSLIP_CMAKE_BUILD_DIR")
        build_dir, targets = self._reuse(reuse) if reuse else self._configure_fresh()
        build = ["cmake", "--build", str(build_dir), "--target", *targets]
        if "CMAKE_BUILD_PARALLEL_LEVEL" not in os.environ:
            build += ["--parallel", str(os.cpu_count() or 2)]
        subprocess.check_call(build)

        built = sorted((build_dir / "python" / "stickslip").glob("_core*.so"), key=os.path.getmtime)
        if not built:
            sys.exit(f"stickslip: the build left no _core*.so in {build_dir / 'python' / 'stickslip'}")
        dest = Path(self.get_ext_fullpath(ext.name))
        dest.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], dest)
        # The command, beside the module: everything in build_lib goes into the
        # wheel (mode bits included), and __main__.py runs it from there.
        if CLI_TARGET in targets:
            cli = build_dir / "stickslip"
            if not cli.is_file():
                sys.exit(f"stickslip: the build left no command {cli}")
            bin_dir = dest.parent / "_bin"
            bin_dir.mkdir(exist_ok=True)
            shutil.copy2(cli, bin_dir / "stickslip")


class SdistWithRevision(sdist):
    """Writes REVISION into the archive: `stickslip --version` built from the
    sdist then names the commit it came from (cmake/source_revision.cmake)."""

    def make_release_tree(self, base_dir, files):
        super().make_release_tree(base_dir, files)
        target = Path(base_dir) / "REVISION"
        if target.exists():  # a hard link to the tree's own file, if any: replace, never write through
            target.unlink()
        revision = _revision() or ((ROOT / "REVISION").read_text().strip() if (ROOT / "REVISION").is_file() else "")
        target.write_text(revision + "\n")


(ROOT / BUILD_BASE).mkdir(exist_ok=True)
setup(
    ext_modules=[CMakeExtension("stickslip._core")],
    cmdclass={"build_ext": CMakeBuild, "sdist": SdistWithRevision},
    setup_requires=_missing_build_tools(),
    options={"build": {"build_base": BUILD_BASE}, "egg_info": {"egg_base": BUILD_BASE}},
)
