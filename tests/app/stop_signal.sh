#!/bin/bash
# A signal ends a running `mpmxdem run` after its current MPM step with a checkpoint (docs/reference/errors.md
# "Stopping a run"), and `--restart latest` continues bit for bit:
#  1. SIGUSR1 to mpiexec (Open MPI forwards it to every rank; what `mpirun` users and Slurm's
#     `--signal=USR1@T` before a time limit send): exit 138, the log names the signal and the
#     checkpoint of the step it stopped at;
#  2. SIGTERM to every rank itself (what Slurm sends at a time limit, through srun): exit 143;
#  3. a restart with --max-steps S from each stopped run gives the results.h5 of a straight run of
#     S steps, byte for byte once the row written at the stop is left out (tests/app/same_rows.py);
#  4. `run --max-wall 4`: the run ends by itself before 4 s, with a checkpoint, exit 75 (and 3.);
#  5. `mpmxdem dem`: SIGUSR2 ends the loading at its next row, with its series and final packing.
# The job never ends by itself (end time 1e5 s of a slow elastic triaxial): only the signal stops it.
# Usage: stop_signal.sh EXE MPIEXEC H5DIFF WORKDIR PYTHON (from the source root; PYTHON with h5py)
set -uo pipefail
exe=$1 mpiexec=$2 h5diff=$3 dir=$4 python=$5
rm -rf "$dir" && mkdir -p "$dir"
fail() { echo "FAIL: $*"; exit 1; }
# The platen at 1 um/s instead of 1 mm/s: a million steps (2500 s) move it 2.5 mm of the 1 m cell.
sed 's/end_time = "2 s"/end_time = "1e5 s"/; s/z = "-1 mm\/s"/z = -1e-6/' jobs/elastic_triaxial.toml > "$dir/job.toml"
grep -q "z = -1e-6" "$dir/job.toml" || fail "the platen of jobs/elastic_triaxial.toml is not the one this test slows"

# The processes whose command line starts with $1 (from /proc: no procps needed).
pids_of() {
  local f cmd
  for f in /proc/[0-9]*/cmdline; do
    cmd=$(tr '\0' ' ' < "$f" 2> /dev/null) || continue
    [[ "$cmd" == "$1"* ]] && echo "${f//[^0-9]/}"
  done
}

# Starts a 2-rank run into $dir/$1 in the background; returns when its stepping loop has begun
# (the farm's first log line comes after the handlers are installed), then lets it step a while.
start() {
  "$mpiexec" -n 2 "$exe" run "$dir/job.toml" --out "$dir/$1" > "$dir/$1.out" 2>&1 &
  pid=$!
  for _ in $(seq 600); do
    grep -q "farm: 8 RVEs" "$dir/$1/log.txt" 2> /dev/null && break
    kill -0 "$pid" 2> /dev/null || fail "$1: the run ended before the signal: $(cat "$dir/$1.out")"
    sleep 0.5
  done
  grep -q "farm: 8 RVEs" "$dir/$1/log.txt" || fail "$1: the run did not start in 300 s"
  sleep 1
}

# Waits for the run of start() (300 s at most) and checks its exit code and its stop.
finish() {  # name code signal
  for _ in $(seq 600); do kill -0 "$pid" 2> /dev/null || break; sleep 0.5; done
  if kill -0 "$pid" 2> /dev/null; then
    kill -9 "$pid"
    fail "$1: still running 300 s after the signal"
  fi
  wait "$pid"
  local rc=$?
  [ "$rc" -eq "$2" ] || fail "$1: exit $rc, expected $2: $(tail -20 "$dir/$1.out")"
  local line
  line=$(grep -- "stopped by $3 at step" "$dir/$1/log.txt") || fail "$1: no 'stopped by $3' line: $(tail -5 "$dir/$1/log.txt")"
  step=$(sed -E 's/.*at step ([0-9]+),.*/\1/' <<< "$line")
  [ -f "$dir/$1/checkpoint_$(printf %010d "$step").h5" ] || fail "$1: no checkpoint of step $step: $(ls "$dir/$1")"
  grep -q "checkpoint_$(printf %010d "$step").h5; continue with" <<< "$line" || fail "$1: $line"
  echo "$1: stopped by $3 at step $step, exit $rc"
  local ended=(ended=signal "signal=$3")
  [ "$rc" -eq 75 ] && ended=(ended=max_wall signal=)
  "$python" tests/app/check_run_summary.py "$dir/$1" "${ended[@]}" "exit_code=$rc" \
    "mpm_steps=$step" "checkpoints~checkpoint_$(printf %010d "$step").h5" ||
    fail "$1: run_summary.json"
}

start usr1
kill -USR1 "$pid"
finish usr1 138 SIGUSR1
usr1_step=$step

start term
ranks=$(pids_of "$exe run $dir/job.toml --out $dir/term")
[ -n "$ranks" ] || fail "term: no rank processes"
[ "$(wc -w <<< "$ranks")" -eq 2 ] || fail "term: expected 2 rank processes: $ranks"
kill -TERM $ranks
finish term 143 SIGTERM
term_step=$step

# --max-wall: the run ends by itself before 4 s of wall time, with a checkpoint, exit 75.
"$mpiexec" -n 2 "$exe" run "$dir/job.toml" --out "$dir/wall" --max-wall 4 > "$dir/wall.out" 2>&1 &
pid=$!
finish wall 75 "--max-wall 0h0m4s"
wall_step=$step

# Each stopped run continued a few steps past where it stopped, against a straight run that far.
for run in usr1 term wall; do
  step=${run}_step
  end=$((${!step} + 7))
  "$mpiexec" -n 2 "$exe" run "$dir/job.toml" --out "$dir/$run" --restart latest --max-steps "$end" \
    > "$dir/$run.restart.out" 2>&1 || fail "$run: restart: $(tail -20 "$dir/$run.restart.out")"
  grep -q "continuing from $dir/$run/checkpoint_" "$dir/$run.restart.out" || fail "$run: restart did not continue"
  "$python" tests/app/check_run_summary.py "$dir/$run" ended=max_steps exit_code=0 "mpm_steps=$end" \
    "restart~$dir/$run/checkpoint_" || fail "$run: run_summary.json of the continued run"
  "$mpiexec" -n 2 "$exe" run "$dir/job.toml" --out "$dir/$run.straight" --max-steps "$end" \
    > "$dir/$run.straight.out" 2>&1 || fail "$run: straight run: $(tail -20 "$dir/$run.straight.out")"
  "$python" tests/app/same_rows.py "$dir/$run.straight/results.h5" "$dir/$run/results.h5" \
    "${!step}" > "$dir/$run.compare" 2>&1 ||
    fail "$run: stopped and continued differs from straight to step $end: $(tail -5 "$dir/$run.compare")"
  echo "$run: continued to step $end: results.h5 identical to a straight run"
done
# `dem` (one process, no mpiexec): SIGUSR2 ends the loading at its next series row; the series
# (CSV and HDF5, readable) and the final packing are written, exit 140.
sed 's/^axial_strain = 0.02/axial_strain = 0.5/' jobs/triaxial_dem_small.toml > "$dir/dem.toml"
"$exe" dem "$dir/dem.toml" --out "$dir/dem" > "$dir/dem.out" 2>&1 &
pid=$!
for _ in $(seq 600); do
  grep -q "DEM steps$" "$dir/dem/log.txt" 2> /dev/null && break  # the loading has begun
  kill -0 "$pid" 2> /dev/null || fail "dem: ended before the signal: $(cat "$dir/dem.out")"
  sleep 0.5
done
sleep 1
kill -USR2 "$pid"
for _ in $(seq 600); do kill -0 "$pid" 2> /dev/null || break; sleep 0.5; done
kill -0 "$pid" 2> /dev/null && { kill -9 "$pid"; fail "dem: still running 300 s after the signal"; }
wait "$pid"
rc=$?
[ "$rc" -eq 140 ] || fail "dem: exit $rc, expected 140: $(tail -20 "$dir/dem.out")"
grep -q "stopped by SIGUSR2 after [0-9]* loading steps" "$dir/dem/log.txt" || fail "dem: no stop line"
[ -s "$dir/dem/final_packing.txt" ] || fail "dem: no final packing"
"$h5diff" "$dir/dem/dem_series.h5" "$dir/dem/dem_series.h5" > /dev/null || fail "dem: dem_series.h5 unreadable"
echo "dem: $(grep -o "stopped by SIGUSR2 after [0-9]* loading steps" "$dir/dem/log.txt"), exit $rc"
echo "stop signal: ok"
