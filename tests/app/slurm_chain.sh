#!/bin/bash
# jobs/slurm/mpmxdem_chain.sbatch under stand-ins for sbatch, srun and scancel (no Slurm here):
# a first link queues the next one, runs the job from the beginning with --restart latest, and
# cancels the queued link once the run has finished; a second link (the run already finished)
# continues from the newest checkpoint with nothing left to do.
# Usage: slurm_chain.sh EXE MPIEXEC WORKDIR (from the source root)
set -euo pipefail
exe=$1 mpiexec=$2 dir=$3
rm -rf "$dir" && mkdir -p "$dir/bin"
sed 's/end_time = "2 s"/end_time = "0.05 s"/' jobs/elastic_triaxial.toml > "$dir/job.toml"
cat > "$dir/bin/sbatch" <<STUB
#!/bin/bash
echo "\$@" >> "$dir/sbatch.log"; echo 1001
STUB
cat > "$dir/bin/scancel" <<STUB
#!/bin/bash
echo "\$@" >> "$dir/scancel.log"
STUB
cat > "$dir/bin/srun" <<STUB
#!/bin/bash
shift  # --cpu-bind=cores
exec "$mpiexec" -n 2 --bind-to none "\$@"
STUB
chmod +x "$dir/bin/"*
fail() { echo "FAIL: $*"; exit 1; }
link() {
  PATH="$dir/bin:$PATH" SLURM_JOB_ID=1000 SLURM_SUBMIT_DIR="$PWD" SLURM_CPUS_PER_TASK=1 \
    JOB="$dir/job.toml" OUT="$dir/out" LINKS=3 LINK=$1 MPMXDEM="$exe" \
    bash jobs/slurm/mpmxdem_chain.sbatch > "$dir/link$1.out" 2>&1 || fail "link $1 exit $?: $(cat "$dir/link$1.out")"
}
link 1
grep -q -- "--dependency=afterany:1000" "$dir/sbatch.log" || fail "next link not queued: $(cat "$dir/sbatch.log")"
grep -q "LINK=2" "$dir/sbatch.log" || fail "next link not numbered 2: $(cat "$dir/sbatch.log")"
grep -q "no checkpoint in $dir/out yet" "$dir/link1.out" || fail "link 1 did not start afresh: $(cat "$dir/link1.out")"
grep -qx "1001" "$dir/scancel.log" || fail "finished run did not cancel the next link"
ls "$dir/out"/checkpoint_*.h5 > /dev/null || fail "no checkpoint written"
link 3  # the last link queues nothing
grep -q "continuing from $dir/out/checkpoint_" "$dir/link3.out" || fail "link 3 did not continue: $(cat "$dir/link3.out")"
[ "$(wc -l < "$dir/sbatch.log")" -eq 1 ] || fail "the last link queued another: $(cat "$dir/sbatch.log")"
echo "slurm chain: ok"
