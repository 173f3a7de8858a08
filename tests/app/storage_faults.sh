#!/bin/bash
# Storage that fails under a coupled run on 2 ranks, at each kind of write: a full disk (ENOSPC)
# at the checkpoint, the rows of results.h5, the grain views, means.csv, points.xmf,
# reactions.csv, the job copy and the lock (tests/app/fail_writes.c, LD_PRELOAD, fails the writes
# of rank processes to the files of one kind once a given number of bytes went to them). In every
# case: exit 4 on every rank with the file and the system's reason, within the test's time (no
# hang), no partial checkpoint left, the checkpoints written before untouched, and
# `run --restart latest` from there ends with results.h5 and the last checkpoint equal to a straight
# run's (h5diff; the checkpoint's state, not its measured costs). Then a real full disk where mount is allowed: a 2 MB tmpfs filled by the run
# itself (whichever write meets it), and a quota-like EDQUOT on the checkpoint.
# Usage: storage_faults.sh EXE MPIEXEC H5DIFF SHIM WORKDIR (from the source root)
set -uo pipefail
exe=$1 mpiexec=$2 h5diff=$3 shim=$4 dir=$5
rm -rf "$dir" && mkdir -p "$dir"
fail() { echo "FAIL: $*"; exit 1; }

# A small coupled job: 8 DEM RVEs, a row every step, a checkpoint every 5, grain views every 10.
sed -e 's/^every = 10$/every = 1\ncheckpoint_every = 5\ncheckpoint_keep = 3/' \
    -e 's/end_time = "0.326 s"/end_time = "0.06 s"/' jobs/triaxial_mpmxdem_small.toml > "$dir/job.toml"
printf '\n[output.grains]\nrves = [0]\nevery = 10\n' >> "$dir/job.toml"
grep -q "checkpoint_every = 5" "$dir/job.toml" || fail "job edit did not apply"

run() {  # run OUT [extra mpiexec args...] -> rc in $rc, output in OUT.txt
  local out=$1; shift
  timeout 300 "$mpiexec" -n 2 --bind-to none "$@" "$exe" run "$dir/job.toml" --out "$out" \
    > "$out.txt" 2>&1
  rc=$?
  [ $rc -eq 124 ] && fail "$out: no answer within 300 s (a hang): $(tail -5 "$out.txt")"
}
run "$dir/straight"
[ $rc -eq 0 ] || fail "straight run: exit $rc: $(tail -5 "$dir/straight.txt")"
last=$(ls "$dir/straight"/checkpoint_*.h5 | tail -1)

# kind, path pattern, bytes before the disk is full, text the error must hold
cases=(
  "checkpoint|checkpoint_0|1200000|checkpoint_0000000010.h5.tmp': No space left on device"
  "results.h5 rows|results.h5|2500000|of '$dir/f_results/results.h5': No space left on device"
  "grain views|/grains/|600000|(RVE of point id 0): cannot write '$dir/f_grainviews/grains/rve_0_step_"
  "means.csv|means.csv|8000|means.csv.tmp': No space left on device"
  "points.xmf|points.xmf|60000|points.xmf.tmp': No space left on device"
  "reactions.csv|reactions.csv|8000|reactions.csv.tmp': No space left on device"
  "job copy|job.toml|0|job.toml.tmp': No space left on device"
  "lock|mpmxdem.lock|0|mpmxdem.lock': No space left on device"
)
printf '%-16s %-5s %-11s %-8s %s\n' "write" "exit" "checkpoint" "restart" "message" > "$dir/table.txt"
i=0
for c in "${cases[@]}"; do
  IFS='|' read -r kind pattern after text <<< "$c"
  i=$((i + 1))
  out="$dir/f_$(echo "$kind" | tr -cd 'a-z')"
  [ "$kind" = "results.h5 rows" ] && out="$dir/f_results"
  text=${text//\$dir/$dir}
  run "$out" -x LD_PRELOAD="$shim" -x MPMXDEM_FAIL_PATH="$pattern" -x MPMXDEM_FAIL_AFTER="$after"
  [ $rc -eq 4 ] || fail "$kind: exit $rc, not 4: $(grep -v '^\[' "$out.txt" | tail -8)"
  for t in "$text" "No space left on device"; do
    grep -qF -- "$t" "$out.txt" || fail "$kind: the message does not say '$t': $(grep -i error "$out.txt")"
  done
  [ "$(grep -c 'exited on signal\|Segmentation\|MPI_ABORT' "$out.txt")" -eq 0 ] || fail "$kind: a rank crashed"
  msg=$(grep -m1 '^error' "$out.txt")
  if [ "$kind" = "lock" ] || [ "$kind" = "job copy" ]; then
    # Refused before the run: nothing of it is left, the directory included.
    [ ! -e "$out" ] || fail "$kind: the refused run left $(ls "$out")"
    printf '%-16s %-5s %-11s %-8s %s\n' "$kind" "$rc" "none yet" "-" "$msg" >> "$dir/table.txt"
    continue
  fi
  ls "$out"/*.tmp "$out"/grains/*.tmp 2> /dev/null && fail "$kind: a partial file is left"
  cp=$(ls "$out"/checkpoint_*.h5 2> /dev/null | tail -1)
  [ -n "$cp" ] || fail "$kind: no checkpoint before the failure"
  "$exe" inspect "$cp" > /dev/null 2>&1 || fail "$kind: $cp does not read back"
  timeout 300 "$mpiexec" -n 2 --bind-to none "$exe" run "$dir/job.toml" --out "$out" --restart latest \
    > "$out.restart.txt" 2>&1 || fail "$kind: restart: exit $?: $(tail -5 "$out.restart.txt")"
  "$h5diff" "$dir/straight/results.h5" "$out/results.h5" > /dev/null ||
    fail "$kind: results.h5 after the restart differs from the straight run's"
  # Every field of the state, not the measured costs and the partition made of them.
  "$h5diff" --exclude-path /rve/cost --exclude-path /rve/partition "$last" "$out/$(basename "$last")" \
    > /dev/null || fail "$kind: the last checkpoint after the restart differs from the straight run's"
  printf '%-16s %-5s %-11s %-8s %s\n' "$kind" "$rc" "$(basename "$cp" .h5 | sed 's/checkpoint_0*//')" "same" "$msg" >> "$dir/table.txt"
done
# A quota (EDQUOT) and a failing device (EIO: every write to the file fails, fsync too) at the
# checkpoint, which HDF5 builds in memory and the system writes in one piece.
for e in "quota|122|Disk quota exceeded|0" "device|5|Input/output error|1"; do
  IFS='|' read -r kind errno text all <<< "$e"
  out="$dir/f_$kind"
  run "$out" -x LD_PRELOAD="$shim" -x MPMXDEM_FAIL_PATH=checkpoint_0 -x MPMXDEM_FAIL_AFTER=1200000 \
    -x MPMXDEM_FAIL_ERRNO="$errno" -x MPMXDEM_FAIL_ALL="$all"
  [ $rc -eq 4 ] || fail "checkpoint, $kind: exit $rc, not 4: $(grep -v '^\[' "$out.txt" | tail -8)"
  grep -qF "checkpoint_0000000010.h5.tmp': $text" "$out.txt" || fail "checkpoint, $kind: $(grep -i error "$out.txt")"
  ls "$out"/*.tmp 2> /dev/null && fail "checkpoint, $kind: a partial file is left"
  printf '%-16s %-5s %-11s %-8s %s\n' "checkpoint, $kind" "$rc" 5 "-" "$(grep -m1 '^error' "$out.txt")" >> "$dir/table.txt"
done

# A disk full from the start: results.h5's first megabyte (its metadata) finds no room. Room is
# reserved before HDF5 opens the file: HDF5 itself never meets the full disk (where it did, its
# failed close made its termination at MPI_Finalize crash: exit 139 instead of 4).
out="$dir/f_results_start"
run "$out" -x LD_PRELOAD="$shim" -x MPMXDEM_FAIL_PATH=results.h5 -x MPMXDEM_FAIL_AFTER=50000
[ $rc -eq 4 ] || fail "results.h5 at the start: exit $rc, not 4: $(grep -v '^\[' "$out.txt" | tail -8)"
grep -qF "no room for the next 1048576 bytes of '$out/results.h5': No space left on device" "$out.txt" ||
  fail "results.h5 at the start: $(grep -i error "$out.txt")"
[ "$(grep -c 'exited on signal\|Segmentation\|MPI_ABORT' "$out.txt")" -eq 0 ] ||
  fail "results.h5 at the start: a rank crashed"
printf '%-16s %-5s %-11s %-8s %s\n' "results.h5 start" "$rc" "none yet" "-" "$(grep -m1 '^error' "$out.txt")" >> "$dir/table.txt"

# A real full disk: a 2 MB tmpfs that the run fills itself (whichever write meets the end).
mnt="$dir/tmpfs"
mkdir -p "$mnt"
if mount -t tmpfs -o size=2m tmpfs "$mnt" 2> /dev/null; then
  trap 'umount "$mnt" 2> /dev/null' EXIT
  run "$mnt/out"
  cp "$mnt/out.txt" "$dir/tmpfs.txt"
  [ $rc -eq 4 ] || fail "tmpfs: exit $rc, not 4: $(grep -v '^\[' "$dir/tmpfs.txt" | tail -8)"
  grep -q "No space left on device" "$dir/tmpfs.txt" || fail "tmpfs: $(grep -i error "$dir/tmpfs.txt")"
  ls "$mnt/out"/*.tmp 2> /dev/null && fail "tmpfs: a partial file is left"
  cp -r "$mnt/out" "$dir/tmpfs_out"
  umount "$mnt"
  cp=$(ls "$dir/tmpfs_out"/checkpoint_*.h5 | tail -1)
  timeout 300 "$mpiexec" -n 2 --bind-to none "$exe" run "$dir/job.toml" --out "$dir/tmpfs_out" \
    --restart latest > "$dir/tmpfs.restart.txt" 2>&1 || fail "tmpfs: restart: exit $?"
  "$h5diff" "$dir/straight/results.h5" "$dir/tmpfs_out/results.h5" > /dev/null ||
    fail "tmpfs: results.h5 after the restart differs from the straight run's"
  printf '%-16s %-5s %-11s %-8s %s\n' "tmpfs of 2 MB" "$rc" "$(basename "$cp" .h5 | sed 's/checkpoint_0*//')" "same" "$(grep -m1 '^error' "$dir/tmpfs.txt")" >> "$dir/table.txt"
  # Full before results.h5: a 600 kB tmpfs holds the job copy, the lock and the log, not the
  # first megabyte of results.h5.
  mount -t tmpfs -o size=600k tmpfs "$mnt"
  run "$mnt/out"
  cp "$mnt/out.txt" "$dir/tmpfs_small.txt"
  umount "$mnt"
  [ $rc -eq 4 ] || fail "tmpfs of 600 kB: exit $rc, not 4: $(grep -v '^\[' "$dir/tmpfs_small.txt" | tail -8)"
  grep -q "No space left on device" "$dir/tmpfs_small.txt" || fail "tmpfs of 600 kB: $(grep -i error "$dir/tmpfs_small.txt")"
  [ "$(grep -c 'exited on signal\|Segmentation\|MPI_ABORT' "$dir/tmpfs_small.txt")" -eq 0 ] ||
    fail "tmpfs of 600 kB: a rank crashed"
  printf '%-16s %-5s %-11s %-8s %s\n' "tmpfs of 600 kB" "$rc" "none yet" "-" "$(grep -m1 '^error' "$dir/tmpfs_small.txt")" >> "$dir/table.txt"
else
  echo "note: mount -t tmpfs is not permitted here: the real full disk was not tried (the shim's cases were)"
fi
cat "$dir/table.txt"
echo "storage faults: ok"
