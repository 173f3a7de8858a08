#!/bin/bash
# Figures of one many-core node, in one run (never a test): what docs/validation/scaling.md section 5 asks
# of a 16-core machine and the DEM thread speed-ups (docs/design/dem.md "Speed").
#
#   tools/bench_node.sh BIN OUT [ROUNDS]
#
# BIN holds mpmxdem, bench_dem and bench_farm (or is a build folder: build/, build/src/dem,
# build/src/farm are looked up); OUT receives raw.txt (every program's output) and summary.txt.
# mpirun comes from PATH; run from the repository root (it reads jobs/ and jobs/packings).
# Sections (about 4 minutes on 16 cores):
#   A. bench_dem, 1000 / 8000 / 27000 spheres: ROUNDS (8) interleaved pairs of 1 and 2 threads,
#      unbound, then 1-16 threads bound to cores (OMP_PROC_BIND=spread, OMP_PLACES=cores);
#   B. mpmxdem bench mpm at 10^4 and 10^5 points on 1-16 threads (rank 0's MPM step);
#   C. bench_farm exchange --rves 10000 on 2, 4, 8, 16 ranks (the scatter and gather);
#   D. strong scaling of a coupled job (docs/data/biaxial_in_turn/biaxial_plane_strain_8x16_in_turn.toml: 512 RVEs of 300
#      spheres, 400 MPM steps) on ranks x threads 1x1 ... 16x1, 1x16, 2x8, 4x4;
#   E. bench_farm checkpoint --micro dem --rves 64 on 16 ranks.
set -u
BIN=$(cd "$1" && pwd)
OUT=$2
ROUNDS=${3:-8}
STEPS=${BENCH_NODE_STEPS:-400}  # MPM steps of section D
mkdir -p "$OUT"
RAW=$OUT/raw.txt
SUM=$OUT/summary.txt
: >"$RAW"
: >"$SUM"
find_bin() {
  for d in "$BIN" "$BIN/src/dem" "$BIN/src/farm"; do
    [ -x "$d/$1" ] && { echo "$d/$1"; return; }
  done
  echo "bench_node: $1 not found under $BIN" >&2
  exit 2
}
MPMXDEM=$(find_bin mpmxdem)
BENCH_DEM=$(find_bin bench_dem)
BENCH_FARM=$(find_bin bench_farm)
NP=$(nproc)
say() { echo "$*" | tee -a "$SUM"; }
log() { tee -a "$RAW"; }
export OMPI_MCA_rmaps_base_oversubscribe=1

say "# node: $(hostname), $NP CPUs, $(date -u +%FT%TZ)"
lscpu | grep -E "Model name|^CPU\(s\)|Thread|Core|Socket|NUMA node\(|L2|L3" | log >/dev/null
lscpu | grep -E "Model name|Thread\(s\) per core|Core\(s\) per socket|L3" | tee -a "$SUM"

# A. DEM step, us per particle-step
dem_us() {  # tiles threads steps [bind]
  local out
  local places=""
  [ -n "${4:-}" ] && places=cores
  out=$(env OMP_NUM_THREADS="$2" OMP_PROC_BIND="${4:-false}" ${places:+OMP_PLACES=$places} \
        "$BENCH_DEM" "" "$1" "$2" "$3" 2>&1)
  echo "dem tiles $1 threads $2 bind ${4:-none}: $out" >>"$RAW"
  echo "$out" | sed -n 's/.*us\/particle-step \([0-9.eE+-]*\).*/\1/p'
}
say "## A. DEM step (bench_dem), us per particle-step"
for spec in "1 6000" "2 1500" "3 500"; do
  set -- $spec
  ones=""; twos=""; ratios=""
  for r in $(seq "$ROUNDS"); do
    a=$(dem_us "$1" 1 "$2"); b=$(dem_us "$1" 2 "$2")
    ones="$ones $a"; twos="$twos $b"
    ratios="$ratios $(awk -v a="$a" -v b="$b" 'BEGIN{printf "%.3f", a/b}')"
  done
  med() { echo "$@" | tr ' ' '\n' | grep . | sort -g | awk '{v[NR]=$1} END{print (NR%2)?v[(NR+1)/2]:(v[NR/2]+v[NR/2+1])/2}'; }
  say "spheres $((1000 * $1 ** 3)) unbound: 1 thread [$ones ] 2 threads [$twos ]"
  say "  speed-ups [$ratios ] median 1 thread $(med $ones) us, 2 threads $(med $twos) us, speed-up $(med $ratios)"
  line="spheres $((1000 * $1 ** 3)) bound to cores:"
  base=""
  for t in 1 2 4 8 16; do
    [ "$t" -gt "$NP" ] && break
    u=$(dem_us "$1" "$t" "$2" spread)
    [ -z "$base" ] && base=$u
    line="$line $t: $u us ($(awk -v a="$base" -v b="$u" 'BEGIN{printf "%.2fx", a/b}'))"
  done
  say "$line"
done

# B. rank 0's MPM step on 1-16 threads
say "## B. mpmxdem bench mpm (ns per point and step)"
for n in 10000 100000; do
  OMP_NUM_THREADS=$NP OMP_PROC_BIND=spread OMP_PLACES=cores timeout 120 "$MPMXDEM" bench mpm \
    --size "$n" --steps $((n > 20000 ? 10 : 30)) 2>&1 | log | grep "^points=" | tee -a "$SUM"
done

# C. the exchange of L and records
say "## C. bench_farm exchange --rves 10000 --steps 50"
for p in 2 4 8 16; do
  [ "$p" -gt "$NP" ] && break
  say "ranks $p: $(OMP_NUM_THREADS=1 timeout 120 mpirun -n "$p" --bind-to core "$BENCH_FARM" exchange \
    --rves 10000 --steps 50 2>&1 | log | grep "per step (medians)")"
done

# D. strong scaling of a coupled job
say "## D. docs/data/biaxial_in_turn/biaxial_plane_strain_8x16_in_turn.toml, $STEPS MPM steps (wall of the steps, from the log)"
tmp=$(mktemp -d)
base=""
for lay in 1x1 2x1 4x1 8x1 16x1 1x16 2x8 4x4; do
  p=${lay%x*}; t=${lay#*x}
  [ $((p * t)) -gt "$NP" ] && continue
  rm -rf "$tmp/run"
  t0=$(date +%s.%N)
  done_line=$(OMP_NUM_THREADS=$t timeout 200 mpirun -n "$p" --bind-to none -x OMP_NUM_THREADS \
    "$MPMXDEM" run docs/data/biaxial_in_turn/biaxial_plane_strain_8x16_in_turn.toml --out "$tmp/run" --max-steps "$STEPS" 2>&1 |
    log | grep "info: done:")
  total=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN{printf "%.1f", b - a}')
  w=$(echo "$done_line" | sed -n 's/.*wall \([0-9.]*\) s;.*/\1/p')
  bal=$(echo "$done_line" | sed -n 's/.*busy) \([0-9.]*\),.*/\1/p')
  [ -z "$base" ] && base=$w
  say "ranks x threads $lay: wall $w s, speed-up $(awk -v a="$base" -v b="$w" 'BEGIN{if (b > 0) printf "%.2f", a/b}'), balance $bal (the whole run, preparation included: $total s)"
done
rm -rf "$tmp"

# E. a checkpoint of DEM RVEs from 16 ranks
say "## E. bench_farm checkpoint --micro dem --rves 64"
p=$((NP < 16 ? NP : 16))
OMP_NUM_THREADS=1 timeout 120 mpirun -n "$p" --bind-to core "$BENCH_FARM" checkpoint --micro dem \
  --rves 64 2>&1 | log | grep -E "checkpoint:|write|read" | tee -a "$SUM"
say "# done $(date -u +%FT%TZ)"
