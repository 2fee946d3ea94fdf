#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# `scripts/figures --drift EXPR`: the figures built on the paper's b(v) run
# another law (Figs. 4 and 9 here, at --quick size), summary.json records the
# law, the stickslip calls carry it, and a figure of pure dry friction, where
# a law does not enter, is refused.
#   bash quick_with_a_drift_law.sh REPO_ROOT OUT_DIR
set -euo pipefail
root="$1"
out="$2"
law="0.342 - c*v*abs(v)"
rm -rf "$out"
bash "$root/scripts/figures" --quick --drift "$law" --drift-params c=0.5 --only fig4,fig9 --out "$out"
for f in fig4.png fig9.png summary.json; do
  [[ -s "$out/$f" ]] || { echo "missing or empty: $out/$f"; exit 1; }
done
/usr/bin/python3 - "$out/summary.json" "$law" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
assert s["meta"]["drift"] == sys.argv[2] and s["meta"]["drift_params"] == "c=0.5", s["meta"]
assert s["fig4"]["scheme_inclusion"] == "resolvent", s["fig4"]["scheme_inclusion"]
# Every stickslip call noted the law it ran (the drift-law note of each run).
notes = [w for ws in s["warnings"].values() for w in ws if w.startswith("drift law (expression)")]
assert notes and all(sys.argv[2] in w for w in notes), notes
print("figures --drift: the law reached fig4 and fig9")
PY
if bash "$root/scripts/figures" --quick --drift "$law" --only table1 --out "$out/refused" 2> "$out/refused.err"; then
  echo "table1 with --drift was not refused"
  exit 1
fi
grep -q "pure dry friction" "$out/refused.err" || { cat "$out/refused.err"; exit 1; }
