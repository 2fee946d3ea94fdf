#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# `scripts/figures --quick` must run and produce every file of the default run:
# Table I (PNG and Markdown), Figs. 2 to 9 as non-empty PNG, and summary.json.
#   bash quick_produces_every_file.sh REPO_ROOT OUT_DIR
set -euo pipefail
root="$1"
out="$2"
rm -rf "$out"
bash "$root/scripts/figures" --quick --out "$out"
missing=0
for f in table1.png table1.md fig2.png fig3.png fig4.png fig5.png fig6.png fig7.png fig8.png fig9.png summary.json; do
  if [[ ! -s "$out/$f" ]]; then
    echo "missing or empty: $out/$f"
    missing=1
  fi
done
for f in "$out"/*.png; do
  if [[ "$(head -c 8 "$f" | od -An -tx1 | tr -d ' \n')" != "89504e470d0a1a0a" ]]; then
    echo "not a PNG: $f"
    missing=1
  fi
done
/usr/bin/python3 -c "import json, sys; json.load(open(sys.argv[1]))" "$out/summary.json" || missing=1
[[ $missing -eq 0 ]] && echo "figures --quick: all files present"
exit $missing
