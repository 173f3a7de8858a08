#!/bin/bash
# jobs/slurm/mpmxdem_chain.sbatch under a real Slurm: a one-node cluster started here (munged,
# slurmctld, slurmd; every file in a temporary directory), the chain submitted with sbatch as a user
# would, its links warned by --signal=USR1 before a 1-minute limit. Checks: the first link stops on
# the warning with a checkpoint (exit 138), the later ones continue (--restart latest), the last one
# finishes (exit 0) and cancels the link it queued; the chain's final checkpoint (h5diff) and
# results.h5 (h5py) are a straight 2-rank mpiexec run's, bit for bit. Exit 77 (skipped): not root,
# or Slurm and munge missing and apt-get cannot install them (no apt-get, no network).
# Usage: slurm_real.sh EXE MPIEXEC H5DIFF PYTHON WORKDIR (from the source root; PYTHON with h5py)
#
# Findings (Debian 12: Slurm 22.05.8, Open MPI 4.1.4):
# - srun makes the ranks one MPI world only with --mpi=pmix (here SLURM_MPI_TYPE=pmix, MpiDefault
#   left at none): with none or pmi2, MPI_Init fails. mpirun in the batch script is no way round:
#   its ranks are no job step, and Slurm's warning goes to the steps (a 53 s run was never warned).
# - sacct needs slurmdbd (accounting_storage/filetxt is gone); `sacct -c` reads the job completion
#   log (jobcomp/filetxt) instead, and `squeue -t all` shows finished jobs for MinJobAge seconds.
# - slurmctld checks time limits every 30 s and sends --signal=USR1@N at the first check less than
#   N + 30 s before the limit: with --time=1 and N = 15, 15 to 45 s into a link. A run of about
#   60 s (sized below) is thus warned in its first link; later links start just after a check and
#   are warned about 30 s in: 2 to 5 links, any number accepted. Where the machine got faster
#   after the calibration (other work ended) and the first link finished unwarned, the chain is
#   run once more at twice the length.
set -uo pipefail
exe=$(realpath "$1") mpiexec=$2 h5diff=$3 python=$4 dir=$(realpath -m "$5")
fail() { echo "FAIL: $*"; exit 1; }
skip() { echo "SKIP: $*"; exit 77; }
rm -rf "$dir" && mkdir -p "$dir"
started=$SECONDS deadline=$((SECONDS + 840))  # a bound of our own, well inside ctest's hour: the trap cleans up
[ "$(id -u)" -eq 0 ] || skip "needs root: slurmd starts the jobs' processes as their user"
"$python" -c "import h5py" || fail "$python: no h5py (Debian: python3-h5py)"

# 1. Slurm and munge, installed where missing (only the packages stay behind).
if ! command -v slurmctld > /dev/null || ! command -v munged > /dev/null; then
  command -v apt-get > /dev/null || skip "slurmctld or munged missing and no apt-get"
  export DEBIAN_FRONTEND=noninteractive
  apt_install() { apt-get install -y -q --no-install-recommends slurm-wlm munge >> "$dir/apt.log" 2>&1; }
  apt_install || { apt-get update -q >> "$dir/apt.log" 2>&1 && apt_install; } ||
    skip "apt-get install slurm-wlm munge failed (no network?): $(tail -3 "$dir/apt.log")"
fi
echo "$(slurmctld -V), $(munged -V 2>&1 | head -1)"

# 2. A one-node cluster: every file in $T (a short path: munge's socket), removed at exit.
T=$(mktemp -d /tmp/mpmxdem-slurm.XXXXXX)
chmod 711 "$T"  # munged wants every directory above its socket searchable by all
mkdir -m 755 "$T/munge" && mkdir "$T/state" "$T/spool" "$T/log" "$T/tmp" && : > "$T/plugstack.conf"
export SLURM_CONF=$T/slurm.conf TMPDIR=$T/tmp  # TMPDIR: Open MPI's session files
# The processes holding a file under $T or $dir (daemons, job steps, ranks): ours by construction.
ours() {
  find /proc/[0-9]*/cwd /proc/[0-9]*/fd -maxdepth 1 \( -lname "$T/*" -o -lname "$dir/*" \) 2> /dev/null |
    cut -d/ -f3 | sort -u | grep -vx -e $$ -e "$BASHPID"
}
cleanup() {
  local pids
  if [ -f "$T/slurmctld.pid" ] && kill -0 "$(cat "$T/slurmctld.pid")" 2> /dev/null; then
    scancel --quiet --user="$(id -un)"  # the job steps end with their jobs
    for _ in $(seq 30); do [ -z "$(squeue -h)" ] && break; sleep 1; done
  fi
  for d in slurmd slurmctld munge/munged; do
    [ -f "$T/$d.pid" ] && kill "$(cat "$T/$d.pid")" 2> /dev/null
  done
  for _ in $(seq 20); do pids=$(ours); [ -z "$pids" ] && break; sleep 0.5; done
  if [ -n "$pids" ]; then
    echo "cleanup: killing leftover processes:" && ps -o pid,args -p "${pids//$'\n'/,}"
    # shellcheck disable=SC2086  # one pid a word
    kill -9 $pids 2> /dev/null
  fi
  cp -r "$T/log" "$dir/slurm-log" 2> /dev/null; cp "$SLURM_CONF" "$dir/slurm-log/" 2> /dev/null
  rm -rf "$T"
  echo "daemons stopped, $T removed; logs in $dir/slurm-log; wall $((SECONDS - started)) s"
}
trap cleanup EXIT
trap 'exit 1' TERM INT
# Two free ports (a real Slurm on this host would hold 6817 and 6818).
free_port() {
  local p
  for p in $(seq "$1" $(($1 + 200))); do (: < "/dev/tcp/127.0.0.1/$p") 2> /dev/null || { echo "$p"; return; }; done
}
ctld_port=$(free_port 16817) && slurmd_port=$(free_port $((ctld_port + 1)))
host=$(hostname -s)
dd if=/dev/urandom of="$T/munge.key" bs=1024 count=1 status=none && chmod 400 "$T/munge.key"
munged --socket="$T/munge/munge.sock" --key-file="$T/munge.key" --pid-file="$T/munge/munged.pid" \
  --log-file="$T/log/munged.log" --seed-file="$T/munge/seed" || fail "munged: $(tail -3 "$T/log/munged.log")"
# proctrack/linuxproc and task/affinity: no cgroups (none in containers), yet srun binds each
# rank to its core as on a cluster (with task/none it cannot, and the sbatch file's OMP_PROC_BIND
# pins both ranks to core 0). KillWait 30 s (the default) from the limit's SIGTERM to SIGKILL: the
# time a link that missed its warning would have for its checkpoint (not needed in these runs).
cat > "$SLURM_CONF" << EOF
ClusterName=mpmxdem-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$(id -un)
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$T/munge/munge.sock
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
PlugStackConfig=$T/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/affinity
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
MpiDefault=none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$T/log/jobcomp.txt
MinJobAge=3600
KillWait=30
ReturnToService=2
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld || fail "slurmctld did not start"
slurmd -N "$host" || fail "slurmd did not start"
for _ in $(seq 30); do [ "$(sinfo -h -o %T 2> /dev/null)" = idle ] && break; sleep 1; done
[ "$(sinfo -h -o %T)" = idle ] || fail "node not idle: $(sinfo; tail -5 "$T"/log/slurm*.log)"
sinfo

# The job: the paper's triaxial (jobs/triaxial_mpmxdem.toml), its end time cut so that the run
# takes about 60 s here (measured on its first 2000 MPM steps): over the 45 s within which the
# first link is warned. mpiexec binds each rank to a core, as srun does in the chain.
job=$dir/job.toml
make_job() {
  sed -e "s|^packing = \"packings/|packing = \"$PWD/jobs/packings/|" \
    -e "s|^end_time = \"195 s\".*|end_time = \"$1 s\"|" jobs/triaxial_mpmxdem.toml > "$job"
  grep -q "^end_time = \"$1 s\"" "$job" || fail "jobs/triaxial_mpmxdem.toml: no end_time of 195 s to cut"
}
straight() {  # out [run options]
  OMP_NUM_THREADS=1 timeout $((deadline - SECONDS)) "$mpiexec" -n 2 --bind-to core \
    "$exe" run "$job" --out "$dir/$1" "${@:2}" > "$dir/$1.out" 2>&1 || fail "$1: $(tail -5 "$dir/$1.out")"
}
make_job 195
straight calibration --max-steps 2000
done_line=$(grep -o "done: 2000 MPM steps, t = [0-9.]* s, wall [0-9.]* s" "$dir/calibration.out") ||
  fail "calibration: no done line"
end=$(awk -v l="$done_line" 'BEGIN { split(l, w, " "); e = w[7] * 60 / w[10]; printf "%.0f", (e > 97 ? 97 : e) }')
make_job "$end"
echo "calibration: $done_line: end_time = \"$end s\" for about 60 s"

# 3. The chain, submitted as the sbatch file's header says, with a short limit and 2 ranks. Each
# link passes CHAIN_SBATCH_ARGS to the link it queues.
CHAIN_SBATCH_ARGS="--nodes=1 --ntasks-per-node=2 --cpus-per-task=1 --time=1 --signal=USR1@15"
export CHAIN_SBATCH_ARGS="$CHAIN_SBATCH_ARGS --output=$dir/%x-%j.out"
export SLURM_MPI_TYPE=pmix
# chain: submit the first link, wait for the chain, follow it link by link (sets links, last, stops).
chain() {
  # shellcheck disable=SC2086
  first=$(sbatch $CHAIN_SBATCH_ARGS --parsable \
    --export="ALL,JOB=$job,OUT=$dir/chain,LINKS=20,LINK=1,MPMXDEM=$exe" jobs/slurm/mpmxdem_chain.sbatch) ||
    fail "sbatch: $first"
  echo "sbatch: submitted job $first (link 1): sbatch $CHAIN_SBATCH_ARGS jobs/slurm/mpmxdem_chain.sbatch"
  # Wait for the chain (until 300 s before the deadline, left for the straight run), printing the
  # queue whenever it changes.
  seen="" q="the queue never read"
  while [ "$SECONDS" -lt $((deadline - 300)) ]; do
    q=$(squeue -h -o "%i %T %r")
    [ "$q" != "$seen" ] && { echo "--- $(date +%T)"; squeue -o "%.6i %.8j %.9T %.6M %.6l %R"; seen=$q; }
    [ -z "$q" ] && break
    sleep 1
  done
  [ -z "$q" ] || fail "the chain did not end in $((SECONDS - started)) s: $q"
  echo "--- squeue -t all (finished jobs, kept MinJobAge s):"
  squeue -t all -o "%.6i %.8j %.10T %.6M %.6l %R"
  echo "--- sacct (needs slurmdbd, none here):"
  sacct -X -o jobid,jobname,state,exitcode,elapsed 2>&1
  echo "--- sacct -c (the job completion log, jobcomp/filetxt):"
  sacct -c -o jobid,jobname,state,exitcode,elapsed,start,end 2>&1

  # 4. Follow the chain: each link's output names the link it queued.
  id=$first links=0 last="" stops=""
  while [ -n "$id" ]; do
    out="$dir/mpmxdem-$id.out" links=$((links + 1))
    [ -f "$out" ] || fail "link $links (job $id) has no output $out"
    next=$(sed -n 's/.*next link queued: job \([0-9]*\).*/\1/p' "$out")
    if grep -q "the run has finished: cancelling the next link" "$out"; then
      last=$id
      grep -q "^\[.*\] info: done: " "$out" || fail "link $links: no 'done:' line: $(tail -5 "$out")"
      [ "$(squeue -h -t all -j "$next" -o %T)" = CANCELLED ] || fail "the link after the last ($next) not cancelled"
      break
    fi
    grep -q "warning: SIGUSR1 received: the run ends after this MPM step" "$out" ||
      fail "link $links (job $id) was not warned: $(tail -5 "$out")"
    grep -q "warning: stopped by SIGUSR1 at step [0-9]*, .*checkpoint .*(exit 138 = 128 + 10)" "$out" ||
      fail "link $links (job $id): no checkpoint on the warning: $(tail -5 "$out")"
    grep -q "the run stopped on signal 10 with a checkpoint: job $next continues it" "$out" ||
      fail "link $links (job $id): the sbatch file did not see exit 138: $(tail -3 "$out")"
    [ "$(squeue -h -t all -j "$id" -o %T)" = FAILED ] || fail "link $links (job $id): not FAILED (exit 138)"
    start="continuing from $dir/chain/" && [ "$links" -eq 1 ] && start="no checkpoint in $dir/chain yet"
    grep -q "$start" "$out" ||
      fail "link $links (job $id) did not start from the beginning (link 1) or continue: $(head -3 "$out")"
    echo "link $links (job $id): $(grep -o "stopped by SIGUSR1 at step [0-9]*, t = [0-9.e+-]* s" "$out"), exit 138"
    stops="$stops $(grep -o "stopped by SIGUSR1 at step [0-9]*" "$out" | grep -o "[0-9]*$")"
    id=$next
  done
}
chain
if [ "$links" -eq 1 ]; then  # finished unwarned: faster than calibrated (other work ended)
  echo "the first link finished unwarned: faster than calibrated; once more at twice the length"
  end=$((2 * end)) && make_job "$end" && rm -rf "$dir/chain"
  chain
fi
[ -n "$last" ] || fail "the chain ended without a finished link"
[ "$links" -ge 2 ] || fail "the first link finished unwarned twice: the run was shorter than calibrated"
out="$dir/mpmxdem-$last.out"
grep -q "continuing from $dir/chain/checkpoint_" "$out" || fail "the last link did not continue"
echo "link $links (job $last): $(grep -o "continuing from [^ ]*" "$out"),"\
  "$(grep -o "done: [0-9]* MPM steps, t = [0-9.]* s" "$out"), exit 0"

# 5. The same job straight through, without Slurm, compared bit for bit. h5diff exits 0 on
# datasets of different lengths ("not comparable"), so its output is checked too. The final
# checkpoints: all but the RVEs' measured costs and their ranks (wall-clock load balancing).
# results.h5: a stopped run writes a row at the step it stops at (docs/reference/errors.md), so
# the chain has a row more per warned link (where the step is no multiple of output.every);
# without those rows, every dataset must be the straight run's, byte for byte (h5py).
straight straight
final=$(basename "$(ls "$dir"/straight/checkpoint_*.h5)")
if ! "$h5diff" -c --exclude-path /rve/cost --exclude-path /rve/partition "$dir/straight/$final" \
  "$dir/chain/$final" > "$dir/h5diff.out" 2>&1 || grep -qi "not comparable" "$dir/h5diff.out"; then
  fail "the chain's $final differs from the straight run's: $(head -20 "$dir/h5diff.out")"
fi
echo "h5diff: the chain's $final identical to the straight run's (but /rve/cost, /rve/partition)"
# shellcheck disable=SC2086  # one step a word
"$python" tests/app/same_rows.py "$dir/straight/results.h5" "$dir/chain/results.h5" $stops ||
  fail "results.h5 differ"
echo "slurm real: ok"
