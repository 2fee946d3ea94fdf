#!/usr/bin/env bash
# Runs each case once alone and once as `mpirun --oversubscribe -np 2` and
# requires the same JSON apart from "work" (timings and thread counts).
#   bash mpi_matches_single_process.sh path/to/stickslip path/to/mpirun
set -euo pipefail
bin="$1"
mpirun="$2"
# Open MPI refuses root unless told; CI runs as root.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# No network here: keep Open MPI on the loopback/shared-memory transports.
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail=0
run_case() {
  local name="$1"
  shift
  "$bin" "$@" --format json --quiet >"$tmp/one.json"
  "$mpirun" --oversubscribe -np 2 "$bin" "$@" --format json --quiet >"$tmp/two.json"
  if /usr/bin/python3 - "$tmp/one.json" "$tmp/two.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for j in (a, b):
    j.pop("work", None)
    for p in j.get("points", []):
        p.pop("work", None)
sys.exit(0 if a == b else 1)
PY
  then
    echo "ok   $name: mpirun -np 2 gives the single-process JSON bit for bit"
  else
    echo "FAIL $name: results differ"
    diff <(tr ',' '\n' <"$tmp/one.json") <(tr ',' '\n' <"$tmp/two.json") | head -20 || true
    fail=1
  fi
}
run_case "diffusivity inclusion" diffusivity --dt 1e-3 --excursions 1000
run_case "diffusivity pdmp" diffusivity --engine pdmp --excursions 1000 --seed 7
run_case "diffusivity --rel-precision" diffusivity --dt 1e-3 --excursions 256 --rel-precision 0.15
run_case "bruteforce" bruteforce --dt 1e-3 --time 1 --trajectories 300
run_case "sweep" sweep --dt 1e-3 --noise 4,6 --tau 0.5 --excursions 200 --allow-capped
# Observables that cannot be split must say so, the same way on every process.
if "$mpirun" --oversubscribe -np 2 "$bin" density --dt 1e-3 --excursions 100 --quiet >"$tmp/d.out" 2>"$tmp/d.err"; then
  echo "FAIL density under mpirun should refuse"; fail=1
elif grep -q "cannot be split across processes" "$tmp/d.err"; then
  echo "ok   density under mpirun refuses with a clear message"
else
  echo "FAIL density under mpirun: unexpected error:"; cat "$tmp/d.err"; fail=1
fi
# A bad --output found by the writing process stops every process (no hang).
if timeout 60 "$mpirun" --oversubscribe -np 2 "$bin" diffusivity --dt 1e-3 --excursions 2000 --quiet \
     --output /nonexistent-dir/x.json >/dev/null 2>"$tmp/o.err"; then
  echo "FAIL bad --output under mpirun should fail"; fail=1
elif [[ $? -eq 124 ]]; then
  echo "FAIL bad --output under mpirun hangs"; fail=1
elif grep -q -- "--output" "$tmp/o.err"; then
  echo "ok   bad --output under mpirun stops every process"
else
  echo "FAIL bad --output under mpirun: unexpected error:"; cat "$tmp/o.err"; fail=1
fi
exit $fail
