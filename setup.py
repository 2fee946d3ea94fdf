# SPDX-License-Identifier: BSD-3-Clause
"""Builds the extension stickslip._core with CMake for `pip install .` (see pyproject.toml).

The metadata lives in pyproject.toml; this file only adds the compiled module.
By default it configures a fresh CMake build under build-pip/ (library and
module only: no tests, no CLI) for the interpreter running pip. With
STICKSLIP_CMAKE_BUILD_DIR=<dir> it reuses that configured build folder instead
(it must have STICKSLIP_PYTHON=ON for this same interpreter) and only builds
the module target there.
"""
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
BUILD_BASE = "build-pip"  # setuptools' own folders; /build*/ is git-ignored
TARGET = "stickslip_python"


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


def _cache_value(cache, key):
    m = re.search(rf"^{re.escape(key)}:[A-Z]+=(.*)$", cache, re.M)
    return m.group(1) if m else None


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        if shutil.which("cmake") is None:
            sys.exit("stickslip: cmake is needed to build the Python module (Debian: cmake)")
        jobs = str(os.cpu_count() or 2)
        reuse = os.environ.get("STICKSLIP_CMAKE_BUILD_DIR")
        if reuse:
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
        else:
            build_dir = Path(self.build_temp).resolve() / "cmake"
            build_dir.mkdir(parents=True, exist_ok=True)
            generator = ["-G", "Ninja"] if shutil.which("ninja") and not (build_dir / "CMakeCache.txt").exists() else []
            subprocess.check_call(["cmake", "-S", str(ROOT), "-B", str(build_dir), *generator,
                                   "-DCMAKE_BUILD_TYPE=Release", "-DSTICKSLIP_BUILD_TESTS=OFF",
                                   "-DSTICKSLIP_BUILD_CLI=OFF", "-DSTICKSLIP_PYTHON=ON",
                                   f"-DPython3_EXECUTABLE={sys.executable}"])
        subprocess.check_call(["cmake", "--build", str(build_dir), "--target", TARGET, "--parallel", jobs])
        built = sorted((build_dir / "python" / "stickslip").glob("_core*.so"), key=os.path.getmtime)
        if not built:
            sys.exit(f"stickslip: the build left no _core*.so in {build_dir / 'python' / 'stickslip'}")
        dest = Path(self.get_ext_fullpath(ext.name))
        dest.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], dest)


(ROOT / BUILD_BASE).mkdir(exist_ok=True)
setup(
    ext_modules=[CMakeExtension("stickslip._core")],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": BUILD_BASE}, "egg_info": {"egg_base": BUILD_BASE}},
)
