#!/usr/bin/env python3
"""2-thread speed-up of the DEM step (docs/design/dem.md "Speed"): interleaved runs of one or
more bench_dem binaries on 1 and 2 threads (per round, each binary `bench_dem "" tiles 1 steps`,
then `... 2 steps`; REPS rounds: all see the same load), printing every run's us per
particle-step, each pair's ratio and the medians. The VM is noisy, and often runs 2 threads in a
slow mode (a 2-thread step as slow as a 1-thread one): the medians are also given separately for
the pairs with a speed-up above --slow (fast spells) and below it.

  tools/mpmxdem-tools bench_dem_speedup build/src/dem/bench_dem --tiles 1 --steps 4000 --reps 9
  tools/mpmxdem-tools bench_dem_speedup OLD/bench_dem NEW/bench_dem --tiles 1 --steps 6000 --reps 20
  tools/mpmxdem-tools bench_dem_speedup build/src/dem/bench_dem --reps 18 --steps 6000 --bind both

--bind yes runs every process with OMP_PROC_BIND=true; --bind both runs each binary unbound and
bound in every round, reported as two entries.
"""
import argparse
import os
import statistics
import subprocess

from .. import readers


def run(binary, tiles, threads, steps, bind=False):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    if bind:
        env["OMP_PROC_BIND"] = "true"
    out = subprocess.run([binary, "", str(tiles), str(threads), str(steps)], env=env,
                         capture_output=True, text=True, check=True).stdout
    return readers.bench_figures(out)["us_per_particle_step"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("binary", nargs="+")
    ap.add_argument("--tiles", type=int, default=1)
    ap.add_argument("--steps", type=int, default=4000)
    ap.add_argument("--reps", type=int, default=9)
    ap.add_argument("--bind", choices=["no", "yes", "both"], default="no",
                    help="OMP_PROC_BIND=true for every run (yes), or runs both ways (both)")
    ap.add_argument("--slow", type=float, default=1.5,
                    help="speed-up below which a pair counts as the VM's slow mode (1.5)")
    a = ap.parse_args()
    binds = {"no": [False], "yes": [True], "both": [False, True]}[a.bind]
    runs = [(b, bind) for b in a.binary for bind in binds]
    one = {r: [] for r in runs}
    two = {r: [] for r in runs}
    for _ in range(a.reps):
        for r in runs:
            one[r].append(run(r[0], a.tiles, 1, a.steps, r[1]))
            two[r].append(run(r[0], a.tiles, 2, a.steps, r[1]))
    for r in runs:
        b = r[0] + (", OMP_PROC_BIND=true" if r[1] else "")
        ratios = [x / y for x, y in zip(one[r], two[r])]
        fast = [r for r in ratios if r >= a.slow]
        slow = [r for r in ratios if r < a.slow]
        print("%s, tiles %d, %d steps: 1 thread %s us"
              % (b, a.tiles, a.steps, " ".join("%.4f" % x for x in one[r])))
        print("2 threads %s us" % " ".join("%.4f" % x for x in two[r]))
        print("speed-ups %s" % " ".join("%.2f" % r for r in ratios))
        print("medians: 1 thread %.4f us, 2 threads %.4f us, speed-up %.2f (%d pairs)"
              % (statistics.median(one[r]), statistics.median(two[r]), statistics.median(ratios),
                 a.reps))
        print("  pairs at or above %.2f: %d, median %s; below: %d, median %s"
              % (a.slow, len(fast), "%.2f" % statistics.median(fast) if fast else "-", len(slow),
                 "%.2f" % statistics.median(slow) if slow else "-"))


if __name__ == "__main__":
    main()
