#!/usr/bin/env python3
"""2-thread speed-up of the DEM step (issue 17, docs/dem.md "Speed"): interleaved runs of one
bench_dem binary on 1 and 2 threads (`bench_dem "" tiles 1 steps`, then `... 2 steps`, REPS
times: both see the same load), printing every run's us per particle-step, each pair's ratio and
the medians. The VM is noisy: read the median ratio.

  tools/bench_dem_speedup.py build/src/dem/bench_dem --tiles 1 --steps 4000 --reps 9
"""
import argparse
import os
import re
import statistics
import subprocess


def run(binary, tiles, threads, steps):
    out = subprocess.run([binary, "", str(tiles), str(threads), str(steps)],
                         env=dict(os.environ, OMP_NUM_THREADS=str(threads)),
                         capture_output=True, text=True, check=True).stdout
    return float(re.search(r"us/particle-step ([0-9.eE+-]+)", out).group(1))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("binary")
    ap.add_argument("--tiles", type=int, default=1)
    ap.add_argument("--steps", type=int, default=4000)
    ap.add_argument("--reps", type=int, default=9)
    a = ap.parse_args()
    one, two = [], []
    for _ in range(a.reps):
        one.append(run(a.binary, a.tiles, 1, a.steps))
        two.append(run(a.binary, a.tiles, 2, a.steps))
    ratios = [x / y for x, y in zip(one, two)]
    print("tiles %d, %d steps: 1 thread %s us" % (a.tiles, a.steps, " ".join("%.4f" % x for x in one)))
    print("2 threads %s us" % " ".join("%.4f" % x for x in two))
    print("speed-ups %s" % " ".join("%.2f" % r for r in ratios))
    print("medians: 1 thread %.4f us, 2 threads %.4f us, speed-up %.2f (%d pairs)"
          % (statistics.median(one), statistics.median(two), statistics.median(ratios), a.reps))


if __name__ == "__main__":
    main()
