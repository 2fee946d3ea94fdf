#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Soak test of exact, order-free merging at scale (not run by CI; about 25
# minutes on a 2-core machine): 1e9 long excursions at the cheapest setting
# (white noise, dt' = 0.1) once as one process and once as `mpirun -np 2`.
# It requires the two JSON results to be equal apart from "work" and prints
# each process's peak resident memory, which must not grow with the run (the
# same run at 1e7 excursions is measured for comparison).
#
#   bash scripts/validation/soak.sh [path/to/stickslip] [excursions]
#
# Its output is what docs/validation.md, "Soak", reports.
set -euo pipefail
bin="${1:-build/stickslip}"
n="${2:-1000000000}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
white=(diffusivity --friction 1 --noise 1 --tau 0 --relaxation inf --bias 0 --dt 0.1 --quiet --format json)
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

peak_kb() { # runs "$@" and prints its peak RSS in kB on stderr as "peak-kb N"
  /usr/bin/python3 -c 'import resource, subprocess, sys
r = subprocess.run(sys.argv[1:]).returncode
print("peak-kb", resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss, file=sys.stderr)
sys.exit(r)' "$@"
}
export -f peak_kb

measure() { # label, output, then the command; prints wall time and peak RSS per process
  local label="$1" out="$2"
  shift 2
  local t0 t1
  t0=$(date +%s.%N)
  "$@" >"$out" 2>"$out.err"
  t1=$(date +%s.%N)
  printf '%-34s %8.1f s   peak RSS per process: %s kB\n' "$label" "$(/usr/bin/python3 -c "print($t1 - $t0)")" \
    "$(awk '/^peak-kb/ {printf "%s ", $2}' "$out.err")"
}

echo "stickslip soak: $n excursions, white noise, dt' = 0.1 ($(nproc) cores)"
measure "one process, $(nproc) threads, 1e7" "$tmp/small1.json" peak_kb "$bin" "${white[@]}" --excursions 10000000
measure "mpirun -np 2, 1 thread each, 1e7" "$tmp/small2.json" \
  mpirun --oversubscribe -np 2 bash -c 'peak_kb "$@"' _ "$bin" "${white[@]}" --threads 1 --excursions 10000000
measure "one process, $(nproc) threads, $n" "$tmp/one.json" peak_kb "$bin" "${white[@]}" --excursions "$n"
measure "mpirun -np 2, 1 thread each, $n" "$tmp/two.json" \
  mpirun --oversubscribe -np 2 bash -c 'peak_kb "$@"' _ "$bin" "${white[@]}" --threads 1 --excursions "$n"
/usr/bin/python3 - "$tmp/one.json" "$tmp/two.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for j in (a, b):
    j.pop("work")
d = a["diffusivity"]
print(f"D = {d['value']!r} +- {d['error']:.3g} (95% interval {d['ci'][0]:.6g} to {d['ci'][1]:.6g}), "
      f"M0 = {a['mobility']['value']:.3g}, E[t1] = {a['mean_duration']['value']!r}, completed {a['completed']}")
if a != b:
    print("FAIL: one process and mpirun -np 2 differ")
    sys.exit(1)
print("ok: mpirun -np 2 gives the single-process JSON bit for bit")
PY
