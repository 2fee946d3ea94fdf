#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# `scripts/figures --static-friction-ratio R`: every stickslip call of a
# figure carries the static friction R times its friction (Figs. 2 and 3 at
# --quick size: both engines), summary.json records R, and a ratio below 1
# is refused.
#   bash quick_with_static_friction.sh REPO_ROOT OUT_DIR
set -euo pipefail
root="$1"
out="$2"
rm -rf "$out"
bash "$root/scripts/figures" --quick --static-friction-ratio 1.5 --only fig2 --out "$out" --cache "$out/cache"
for f in fig2.png summary.json; do
  [[ -s "$out/$f" ]] || { echo "missing or empty: $out/$f"; exit 1; }
done
/usr/bin/python3 - "$out" <<'PY'
import glob, json, os, sys
out = sys.argv[1]
s = json.load(open(os.path.join(out, "summary.json")))
assert s["meta"]["static_friction_ratio"] == 1.5, s["meta"]
runs = [json.load(open(f)) for f in glob.glob(os.path.join(out, "cache", "*.json"))]
assert runs, "no stickslip results cached"
for r in runs:
    p = r["params"]
    assert abs(p["static_friction"] - 1.5 * p["friction"]) < 1e-12 * p["friction"], p
print("figures --static-friction-ratio: %d stickslip calls carried 1.5 times the friction" % len(runs))
PY
if bash "$root/scripts/figures" --quick --static-friction-ratio 0.5 --only fig2 --out "$out/refused" 2> "$out/refused.err"; then
  echo "--static-friction-ratio 0.5 was not refused"
  exit 1
fi
grep -q "static-friction-ratio must be" "$out/refused.err" || { cat "$out/refused.err"; exit 1; }
