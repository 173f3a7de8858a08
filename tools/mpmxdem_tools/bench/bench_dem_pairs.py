#!/usr/bin/env python3
"""Paired DEM speed runs of two bench_dem binaries (docs/design/dem.md, "Speed").

Per repetition runs `OLD "" tiles threads steps` then `NEW ...` (alternating, so both see the
same load) and prints the medians of wall and CPU microseconds per particle-step and the median
of the per-pair ratios old/new. The machine is noisy (up to 30 % run to run): compare ratios.

  tools/mpmxdem-tools bench_dem_pairs OLD_BENCH_DEM NEW_BENCH_DEM --tiles 1 --steps 4000 --reps 7 [--threads 1]
"""
import argparse
import os
import statistics
import subprocess

from .. import readers


def run(binary, tiles, threads, steps):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    out = subprocess.run([binary, "", str(tiles), str(threads), str(steps)], env=env,
                         capture_output=True, text=True, check=True).stdout
    fig = readers.bench_figures(out)
    n = fig["spheres"]
    return n, fig["us_per_particle_step"], fig["cpu_s"] / steps / n * 1e6


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--tiles", type=int, default=1)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--reps", type=int, default=5)
    a = ap.parse_args()
    res = {"old": [], "new": []}
    for _ in range(a.reps):
        for name in ("old", "new"):
            n, wall, cpu = run(getattr(a, name), a.tiles, a.threads, a.steps)
            res[name].append((wall, cpu))
            print(f"{name} spheres {n} threads {a.threads} wall_us {wall:.4f} cpu_us {cpu:.4f}",
                  flush=True)
    for k, label in ((0, "wall"), (1, "cpu")):
        old = [r[k] for r in res["old"]]
        new = [r[k] for r in res["new"]]
        ratio = statistics.median(o / m for o, m in zip(old, new))
        print(f"{label}: old median {statistics.median(old):.4f} us, new median "
              f"{statistics.median(new):.4f} us, median ratio old/new {ratio:.3f} ({a.reps} pairs)")


if __name__ == "__main__":
    main()
