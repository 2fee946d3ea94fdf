#!/usr/bin/env bash
# Runs each case once alone and once as `mpirun --oversubscribe -np N` and
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
  local name="$1" np="$2"
  shift 2
  "$bin" "$@" --format json --quiet >"$tmp/one.json"
  "$mpirun" --oversubscribe -np "$np" "$bin" "$@" --format json --quiet >"$tmp/two.json"
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
    echo "ok   $name: mpirun -np $np gives the single-process JSON bit for bit"
  else
    echo "FAIL $name: results differ"
    diff <(tr ',' '\n' <"$tmp/one.json") <(tr ',' '\n' <"$tmp/two.json") | head -20 || true
    fail=1
  fi
}
run_case "diffusivity inclusion" 2 diffusivity --dt 1e-3 --excursions 1000
run_case "diffusivity inclusion" 3 diffusivity --dt 1e-3 --excursions 1000
run_case "diffusivity inclusion" 1 diffusivity --dt 1e-3 --excursions 1000
run_case "diffusivity pdmp" 3 diffusivity --engine pdmp --excursions 1000 --seed 7
run_case "diffusivity event scheme" 2 diffusivity --scheme event --dt 2e-2 --excursions 500
run_case "diffusivity --rel-precision" 3 diffusivity --dt 1e-3 --excursions 256 --rel-precision 0.15
run_case "bruteforce" 2 bruteforce --dt 1e-3 --time 1 --trajectories 300
run_case "sweep" 3 sweep --dt 1e-3 --noise 4,6 --tau 0.5 --excursions 200 --allow-capped
# The observables merge exactly too, so they split across processes as well.
run_case "density" 3 density --dt 1e-3 --excursions 200 --bins 6
run_case "density pdmp" 2 density --engine pdmp --excursions 200 --bins 6 --sample-dt 1e-3
run_case "correlation" 3 correlation --dt 1e-3 --excursions 200 --lags 4
run_case "moments" 2 moments --dt 1e-3 --trajectories 300 --density --bins 5
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
