#!/usr/bin/python3
"""Speed of the contact laws, in rounds: bench_dem with the CohFrict law, bench_dem with
Hertz-Mindlin, and YADE's Hertz-Mindlin (tools/mpmxdem_tools/references/yade_triax_hertz_mindlin.py --bench-steps), one
thread each, on the 1000-sphere packings of the triaxial comparisons during triaxial loading at
I = 2.5e-4. Prints every round and the median and range of each (a benchmark: never a test).

Usage (from the repository, after tools/dev build; YADE from the Debian package):
  tools/mpmxdem-tools bench_contact_laws [--rounds 3] [--steps 3000] [--no-yade]
      [--bench build/src/dem/bench_dem]
"""
import argparse
import os
import statistics
import subprocess

from .. import readers
from ..paths import ROOT

BENCH = os.path.join(ROOT, "build", "src", "dem", "bench_dem")
HM_PACKING = os.path.join(ROOT, "jobs", "packings", "packing_N1000_hertz_mindlin.txt")


def run(cmd):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    out = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT, check=True).stdout
    return readers.bench_figures(out)["us_per_particle_step"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--steps", type=int, default=3000)
    ap.add_argument("--no-yade", action="store_true")
    ap.add_argument("--bench", default=BENCH, help="the bench_dem binary (default: build/src/dem/bench_dem)")
    a = ap.parse_args()
    cases = {
        "mpmxdem, CohFrict": [a.bench, "", "1", "1", str(a.steps), "cohfrict"],
        "mpmxdem, Hertz-Mindlin": [a.bench, "", "1", "1", str(a.steps), "hertz_mindlin"],
    }
    if not a.no_yade:
        cases["YADE 2023.02a, Hertz-Mindlin"] = [
            "yade", "-j1", "-n", "-x", "tools/mpmxdem_tools/references/yade_triax_hertz_mindlin.py", "--packing", HM_PACKING,
            "--bench-steps", str(a.steps)]
    times = {k: [] for k in cases}
    for r in range(a.rounds):
        for name, cmd in cases.items():
            times[name].append(run(cmd))
            print(f"round {r + 1}: {name}: {times[name][-1]:.4f} us/particle-step", flush=True)
    print("| code and law | us per particle-step, median (range) |")
    print("|---|---|")
    for name, t in times.items():
        print(f"| {name} | {statistics.median(t):.3f} ({min(t):.3f}-{max(t):.3f}) |")


if __name__ == "__main__":
    main()
