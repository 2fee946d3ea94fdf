#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The sanitizer checks, outside CI (they take too long for .ci/run on 2 cores;
# docs/validation.md, "Fuzzing and sanitizers", has the timings and results).
#
#   bash scripts/sanitizers.sh          # both steps below
#   bash scripts/sanitizers.sh asan     # 1. only
#   bash scripts/sanitizers.sh fuzz     # 2. only
#
# 1. asan: the `asan` preset (build-asan/: RelWithDebInfo, AddressSanitizer and
#    UndefinedBehaviorSanitizer, no recovery, leak checks on), then the unit and
#    command-line tests under it (ctest --preset asan: labels unit and cli).
#    Any report fails the test it comes from.
# 2. fuzz: the `fuzz` preset (build-fuzz/, clang++ with libFuzzer) and its
#    smoke runs (ctest --preset fuzz: label fuzz): each target over its corpus,
#    then mutations. Skipped, with a note, when clang++ or libFuzzer is missing
#    (Debian: apt-get install clang libclang-rt-dev).
#
# Environment: STICKSLIP_JOBS (build jobs; default all cores),
# STICKSLIP_FUZZ_SECONDS and STICKSLIP_FUZZ_RUNS (per fuzz target; defaults
# 20 and 20000; e.g. STICKSLIP_FUZZ_SECONDS=3600 STICKSLIP_FUZZ_RUNS=-1 for an
# hour each, -1 runs meaning no limit). A longer campaign by hand:
#   build-fuzz/tests/fuzz/fuzz_cli -dict=tests/fuzz/stickslip.dict -max_len=4096 \
#     -timeout=10 new-inputs/ tests/fuzz/corpus/cli
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

what="${1:-all}"
case "$what" in asan | fuzz | all) ;; *) echo "usage: $0 [asan|fuzz|all]" >&2; exit 2 ;; esac

bash scripts/install-deps.sh
JOBS="${STICKSLIP_JOBS:-$(nproc 2>/dev/null || echo 2)}"
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi

configure() { # preset, build dir, extra args
  local preset=$1 dir=$2
  shift 2
  if [[ -f "$dir/CMakeCache.txt" ]]; then
    cmake --preset "$preset" "$@" >/dev/null
  else
    cmake --preset "$preset" "${generator[@]}" "$@"
  fi
}

if [[ "$what" == asan || "$what" == all ]]; then
  start=$SECONDS
  configure asan build-asan
  cmake --build --preset asan --parallel "$JOBS"
  built=$SECONDS
  ctest --preset asan
  echo "sanitizers: asan: built in $((built - start)) s, unit and cli tests passed in $((SECONDS - built)) s"
fi

if [[ "$what" == fuzz || "$what" == all ]]; then
  probe="$(mktemp -d)"
  trap 'rm -rf "$probe"' EXIT
  echo 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }' >"$probe/p.cpp"
  if ! command -v clang++ >/dev/null 2>&1 ||
     ! clang++ -fsanitize=fuzzer,address,undefined "$probe/p.cpp" -o "$probe/p" >/dev/null 2>&1; then
    echo "sanitizers: no clang++ with libFuzzer, fuzz step skipped (Debian: apt-get install clang libclang-rt-dev)"
    exit 0
  fi
  start=$SECONDS
  configure fuzz build-fuzz -DSTICKSLIP_FUZZ_SECONDS="${STICKSLIP_FUZZ_SECONDS:-20}" \
    -DSTICKSLIP_FUZZ_RUNS="${STICKSLIP_FUZZ_RUNS:-20000}"
  cmake --build --preset fuzz --parallel "$JOBS"
  built=$SECONDS
  ctest --preset fuzz
  echo "sanitizers: fuzz: built in $((built - start)) s, smoke runs passed in $((SECONDS - built)) s"
fi
