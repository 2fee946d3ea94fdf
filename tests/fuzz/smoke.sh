#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# A bounded libFuzzer run (ctest label "fuzz"): the corpus first, then
# mutations, until RUNS inputs or SECONDS seconds.
#
#   bash tests/fuzz/smoke.sh FUZZER CORPUS DICT WORKDIR [RUNS] [SECONDS] [MAX_LEN]
#
# New inputs and any crash, leak, timeout or out-of-memory input go under
# WORKDIR (new/, artifacts/), never into CORPUS.
set -euo pipefail
fuzzer=$1 corpus=$2 dict=$3 work=$4 runs=${5:-20000} seconds=${6:-20} max_len=${7:-4096}
rm -rf "$work"
mkdir -p "$work/new" "$work/artifacts"
status=0
"$fuzzer" -dict="$dict" -runs="$runs" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -max_len="$max_len" -artifact_prefix="$work/artifacts/" -print_final_stats=1 "$work/new" "$corpus" || status=$?
for f in "$work"/artifacts/*; do
  [[ -e $f ]] || continue
  echo "smoke: the input that failed, $f:"
  od -c "$f" | head -40
done
exit "$status"
