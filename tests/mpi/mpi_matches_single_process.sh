#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Runs each case once alone and once as `mpirun --oversubscribe -np N` and
# requires the same JSON apart from "work" (timings and thread counts) and the
# provenance ("command", "settings": how each run was asked for).
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
for j in (a, b):  # less how the run was asked for (command line, settings) and its timings
    for k in ("work", "command", "settings"):
        j.pop(k, None)
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
run_case "diffusivity inclusion" 2 diffusivity --scheme resolvent --dt 1e-3 --excursions 1000
run_case "diffusivity inclusion" 3 diffusivity --scheme resolvent --dt 1e-3 --excursions 1000
run_case "diffusivity inclusion" 1 diffusivity --scheme resolvent --dt 1e-3 --excursions 1000
run_case "diffusivity pdmp" 3 diffusivity --engine pdmp --excursions 1000 --seed 7
run_case "diffusivity event scheme" 2 diffusivity --scheme event --dt 2e-2 --excursions 500
run_case "diffusivity defaults (event scheme, dt auto)" 2 diffusivity --excursions 500
run_case "diffusivity --rel-precision" 3 diffusivity --scheme resolvent --dt 1e-3 --excursions 256 --rel-precision 0.15
run_case "bruteforce" 2 bruteforce --scheme resolvent --dt 1e-3 --time 1 --trajectories 300
run_case "sweep" 3 sweep --scheme resolvent --dt 1e-3 --noise 4,6 --tau 0.5 --excursions 200 --allow-capped
# The observables merge exactly too, so they split across processes as well.
run_case "density" 3 density --scheme resolvent --dt 1e-3 --excursions 200 --bins 6
run_case "density pdmp" 2 density --engine pdmp --excursions 200 --bins 6 --sample-dt 1e-3
run_case "correlation" 3 correlation --scheme resolvent --dt 1e-3 --excursions 200 --lags 4
run_case "moments" 2 moments --scheme resolvent --dt 1e-3 --trajectories 300 --density --bins 5
run_case "spectrum" 3 spectrum --engine inclusion --excursions 300 --frequencies 0,1,10
run_case "spectrum pdmp" 2 spectrum --engine pdmp --excursions 100 --sample-dt 1e-2 --frequencies 0.5
# Killed and resumed across process counts: a run checkpointed by 2
# processes, killed (SIGKILL) a third of its wall time after it started, then
# resumed by 3 processes (1 thread each), prints the single-process JSON.
resume_case() {
  local name="$1"
  shift
  local t0 t1 secs
  t0=$(date +%s.%N)
  "$bin" "$@" --format json --quiet >"$tmp/one.json"
  t1=$(date +%s.%N)
  secs=$(/usr/bin/python3 -c "print(max(0.2, ($t1 - $t0) / 3))")
  rm -f "$tmp/run.ckpt"
  "$mpirun" --oversubscribe -np 2 "$bin" "$@" --threads 1 --format json --quiet \
    --checkpoint "$tmp/run.ckpt" --checkpoint-every 0.02 >/dev/null 2>&1 &
  local launcher=$!
  # The first checkpoint is written before any work: from then on, a third of the run.
  for _ in $(seq 300); do [[ -s "$tmp/run.ckpt" ]] && break; sleep 0.1; done
  sleep "$secs"
  pkill -KILL -f -- "--checkpoint $tmp/run.ckpt" 2>/dev/null || true
  kill -KILL "$launcher" 2>/dev/null || true
  wait "$launcher" 2>/dev/null || true
  if [[ ! -s "$tmp/run.ckpt" ]]; then echo "FAIL $name: no checkpoint written before the kill"; fail=1; return; fi
  "$mpirun" --oversubscribe -np 3 "$bin" "$@" --threads 1 --format json --quiet --resume "$tmp/run.ckpt" \
    >"$tmp/two.json"
  if /usr/bin/python3 - "$tmp/one.json" "$tmp/two.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
resumed = b["work"].get("resumed_samples", 0)
for j in (a, b):  # less how the run was asked for (command line, settings) and its timings
    for k in ("work", "command", "settings"):
        j.pop(k, None)
    for p in j.get("points", []):
        p.pop("work", None)
print(f"     (resumed {resumed} samples from the checkpoint)")
sys.exit(0 if a == b else 1)
PY
  then
    echo "ok   $name: mpirun -np 2 killed, resumed with -np 3, gives the single-process JSON bit for bit"
  else
    echo "FAIL $name: resumed results differ"
    diff <(tr ',' '\n' <"$tmp/one.json") <(tr ',' '\n' <"$tmp/two.json") | head -20 || true
    fail=1
  fi
}
resume_case "resume diffusivity" diffusivity --scheme resolvent --dt 1e-2 --excursions 100000
resume_case "resume density" density --scheme resolvent --dt 1e-2 --excursions 30000 --bins 8
# Memory in constant space: the peak resident set of each process of
# `mpirun -np 2` at 1e7 excursions (white noise, dt' = 0.1, the cheapest
# setting) is within twice that of `mpirun -np 1` (the same MPI libraries)
# and within 1.5 times its own at 1e5 excursions; their results are bitwise
# equal. Before the exact sums each process gathered every block's record:
# 127 MB per process at 1e7 (6.7 MB for one process).
peak_kb() { # runs "$2 ..." and writes its peak RSS (kB) to the file DIR/peak.PID, DIR = $1
  # (one file per process: two processes' lines on one shared stderr can interleave)
  /usr/bin/python3 -c 'import os, resource, subprocess, sys
r = subprocess.run(sys.argv[2:]).returncode
with open(os.path.join(sys.argv[1], "peak.%d" % os.getpid()), "w") as f:
    print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss, file=f)
sys.exit(r)' "$@"
}
export -f peak_kb
max_peak() { cat "$1"/peak.* 2>/dev/null | sort -n | tail -1; } # the largest peak of the processes of one run
memory_case() {
  local white=(diffusivity --friction 1 --noise 1 --tau 0 --relaxation inf --bias 0 --scheme resolvent --dt 0.1 --threads 1 --quiet
               --format json)
  local one two small
  mkdir -p "$tmp/p1" "$tmp/p2" "$tmp/p3"
  "$mpirun" --oversubscribe -np 1 bash -c 'peak_kb "$@"' _ "$tmp/p1" "$bin" "${white[@]}" --excursions 10000000 \
    >"$tmp/m1.json" 2>"$tmp/m1.err"
  "$mpirun" --oversubscribe -np 2 bash -c 'peak_kb "$@"' _ "$tmp/p2" "$bin" "${white[@]}" --excursions 10000000 \
    >"$tmp/m2.json" 2>"$tmp/m2.err"
  "$mpirun" --oversubscribe -np 2 bash -c 'peak_kb "$@"' _ "$tmp/p3" "$bin" "${white[@]}" --excursions 100000 \
    >/dev/null 2>"$tmp/m3.err"
  one=$(max_peak "$tmp/p1")
  two=$(max_peak "$tmp/p2")
  small=$(max_peak "$tmp/p3")
  if [[ -z "$one" || -z "$two" || -z "$small" ]]; then
    echo "FAIL memory: no peak measured"; cat "$tmp/m1.err" "$tmp/m2.err"; fail=1; return
  fi
  echo "     peak RSS per process: -np 1 at 1e7 ${one} kB, -np 2 at 1e7 ${two} kB, -np 2 at 1e5 ${small} kB"
  if (( two > 2 * one || 2 * two > 3 * small )); then
    echo "FAIL memory: -np 2 at 1e7 excursions peaks at ${two} kB per process"; fail=1
  elif ! /usr/bin/python3 -c 'import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
[j.pop(k, None) for j in (a, b) for k in ("work", "command", "settings")]; sys.exit(a != b)' "$tmp/m1.json" "$tmp/m2.json"; then
    echo "FAIL memory: -np 1 and -np 2 at 1e7 excursions differ"; fail=1
  else
    echo "ok   memory: -np 2 at 1e7 excursions in constant memory, bitwise equal to -np 1"
  fi
}
memory_case
# A bad --output found by the writing process stops every process (no hang).
if timeout 60 "$mpirun" --oversubscribe -np 2 "$bin" diffusivity --scheme resolvent --dt 1e-3 --excursions 2000 --quiet \
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
