#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# bench/gpu_checks.sh -- the device checks of issue 14 (docs/gpu.md), in one
# short run on a machine with an NVIDIA GPU (H100/H200 class; sm_90):
#   1. builds gpu_check twice, each a minimal configuration (no CLI, tests,
#      docs or Python): with STICKSLIP_PORTABLE_MATH=ON, where the CPU's
#      kernels take exp/log/log1p from the same functions as the device, and
#      as by default (glibc on the CPU);
#   2. the bitwise comparisons of GPU and CPU on every case (Fig. 2 with stop
#      rules Q and P, white noise, capped excursions from an odd first index
#      with a partial block, the event scheme): with portable math they must
#      be equal (exit 1 otherwise); the default build shows how often glibc
#      makes the CPU differ;
#   3. the speed rows: device-only excursions and steps per second of each
#      case, kernel alone and whole call, next to the CPU on --cpu-threads 2
#      (the issue's 2-core reference) measured in the same run.
# Usage: bash bench/gpu_checks.sh [--excursions N=4096] [--bench N=262144] [--jobs J]
# Output: everything under $OUT (default .device-out/gpu-checks): the two
# gpu_check reports and build logs. Exit: 0 equal with portable math, 1 a
# difference, 2 no CUDA device, 3 a build or other error.
set -uo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${OUT:-$root/.device-out}/gpu-checks
excursions=4096
bench=262144
jobs=$(nproc 2>/dev/null || echo 4)
while [ $# -gt 0 ]; do
  case "$1" in
    --excursions) excursions=$2; shift 2 ;;
    --bench) bench=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    *) echo "usage: bash bench/gpu_checks.sh [--excursions N] [--bench N] [--jobs J]" >&2; exit 3 ;;
  esac
done
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$out/nvidia-smi.txt" 2>&1 || true
cat "$out/nvidia-smi.txt"

build() { # build DIR PORTABLE
  local dir=$1 portable=$2 t0=$SECONDS
  local gen=()
  command -v ninja > /dev/null && gen=(-G Ninja)
  if ! cmake -S "$root" -B "$dir" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release -DSTICKSLIP_CUDA=ON \
        -DSTICKSLIP_PORTABLE_MATH="$portable" -DSTICKSLIP_BUILD_CLI=OFF -DSTICKSLIP_BUILD_TESTS=OFF \
        -DSTICKSLIP_BUILD_DOCS=OFF -DSTICKSLIP_PYTHON=OFF > "$dir.configure.log" 2>&1 ||
     ! cmake --build "$dir" --target gpu_check -j "$jobs" > "$dir.build.log" 2>&1; then
    echo "gpu_checks: building $dir failed; see $dir.configure.log and $dir.build.log" >&2
    tail -20 "$dir.configure.log" "$dir.build.log" >&2
    exit 3
  fi
  echo "built $dir in $((SECONDS - t0)) s"
}

build "$out/build-portable" ON
build "$out/build-default" OFF

echo
echo "== 1. STICKSLIP_PORTABLE_MATH=ON: GPU must equal CPU bit for bit; speed rows =="
"$out/build-portable/gpu_check" --excursions "$excursions" --cpu-threads 2 --bench "$bench" | tee "$out/gpu_check_portable.txt"
status=${PIPESTATUS[0]}
if [ "$status" -eq 2 ]; then exit 2; fi

echo
echo "== 2. default build (glibc on the CPU): differences come from glibc's misroundings =="
"$out/build-default/gpu_check" --excursions "$excursions" --cpu-threads "$jobs" | tee "$out/gpu_check_default.txt"

echo
echo "gpu_checks: portable-math comparison exit status $status (0: all bitwise equal)"
exit "$status"
