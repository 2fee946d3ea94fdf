#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs the Debian packages stickslip needs to build and test, and only the
# missing ones. Idempotent: when everything is present it only checks and
# exits (no apt-get update, no root needed).
#
#   bash scripts/install-deps.sh
#
# Set STICKSLIP_SKIP_DEPS=1 to skip the check (e.g. on a non-Debian system with
# the dependencies installed by other means).
set -euo pipefail

PACKAGES=(
  cmake               # build system (>= 3.20)
  g++                 # C++20 compiler
  ninja-build         # faster builds (optional; make is used without it)
  libgtest-dev        # GoogleTest: the test suite
  libbenchmark-dev    # Google Benchmark: bench/ kernels
  librandom123-dev    # Random123: Philox counter-based generator (header-only)
  libcli11-dev        # CLI11: the command-line parser
  libtomlplusplus-dev # toml++: --config files (TOML)
  nlohmann-json3-dev  # nlohmann/json: JSON reports
  libboost-dev        # Boost.Math (header-only): quadrature and distributions
  libmuparser-dev     # muParser: drift laws b(v) given as expressions (--drift)
  libeigen3-dev       # Eigen (header-only): sparse LU of the Kolmogorov grid solver
  python3             # Debian's /usr/bin/python3: figures and validation scripts
  python3-numpy       # arrays for the figures, the NumPy baseline of bench/
  python3-matplotlib  # the paper's figures (scripts/figures)
  python3-dev         # Python headers for the `stickslip` Python module
  pybind11-dev        # pybind11: the Python module
  python3-pip         # `pip install .` of the Python module
  python3-setuptools  # build backend of `pip install .` (setup.py drives CMake)
  python3-wheel       # idem
  python3-venv        # the pip test installs the sdist into a fresh venv (ctest -L pip)
  libopenmpi-dev      # MPI: `mpirun -np P stickslip diffusivity ...` (STICKSLIP_MPI)
  openmpi-bin         # mpirun, for the MPI test
  doxygen             # the C++ API reference: `cmake --build build --target docs` (label docs)
  python3-nbconvert   # examples/quickstart.ipynb: notebook tooling (jupyter nbconvert)
  python3-nbclient    # runs the notebook in its test (python/tests/test_notebook.py)
  python3-ipykernel   # the Python kernel the notebook runs in
  python3-jsonschema  # the JSON reports checked against schema/report.schema.json (ctest -R reports_match_schema)
)

if [[ "${STICKSLIP_SKIP_DEPS:-0}" == 1 ]]; then
  echo "install-deps: STICKSLIP_SKIP_DEPS=1, not checking packages"
  exit 0
fi

if ! command -v dpkg-query >/dev/null 2>&1 || ! command -v apt-get >/dev/null 2>&1; then
  echo "install-deps: no dpkg/apt-get here (not Debian/Ubuntu); install these by other means:" >&2
  echo "  ${PACKAGES[*]}" >&2
  exit 0
fi

missing=()
for pkg in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$pkg")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

if [[ $(id -u) -eq 0 ]]; then
  SUDO=()
elif command -v sudo >/dev/null 2>&1; then
  SUDO=(sudo)
else
  echo "install-deps: missing packages: ${missing[*]}" >&2
  echo "install-deps: not root and no sudo; install them as root: apt-get install ${missing[*]}" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}" </dev/null
echo "install-deps: installed ${missing[*]}"
