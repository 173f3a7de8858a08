#!/usr/bin/python3
"""Pure DEM plane-strain biaxial tests of the RVE samples an MPM x DEM biaxial job uses (seeds
1..N of docs/data/biaxial_dem/biaxial_dem_300.toml, i.e. the pool of `dem.initial_state.samples`
= N, sample k with seed 1 + k), then their mean with tools/mpmxdem_tools/analysis/biaxial_seed_mean.py: the reference of
docs/validation/biaxial.md, "Which pure DEM".

  tools/mpmxdem-tools biaxial_dem_seeds OUT_DIR [--samples 16] [--inertial-number 2.5e-4] [--strain 0.06]
                             [--exe build/mpmxdem] [--mean MEAN.csv]
                             [--spheres 300] [--pressure 100]   (the RVEs of another job: the
                             footing's are 100 spheres at 50 kPa, docs/validation/footing.md)

Each test runs on one thread (about 4 s for 300 spheres to 6 % at 2.5e-4 on an idle core).
"""
import argparse
import os
import re
import subprocess
import sys

from ..paths import DATA, MPMXDEM, tool_command

BASE = os.path.join(DATA, "biaxial_dem", "biaxial_dem_300.toml")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--samples", type=int, default=16)
    ap.add_argument("--inertial-number", default="2.5e-4")
    ap.add_argument("--strain", default="0.06")
    ap.add_argument("--lateral-tolerance", default="0.1")
    ap.add_argument("--exe", default=MPMXDEM)
    ap.add_argument("--mean", default=None, help="default: OUT/mean.csv")
    ap.add_argument("--spheres", type=int, default=300, help="spheres per sample")
    ap.add_argument("--pressure", type=float, default=100.0,
                    help="preparation and confining pressure [kPa]")
    a = ap.parse_args()
    base = open(BASE).read()
    base = re.sub(r"(?m)^spheres = 300$", f"spheres = {a.spheres}", base)
    base = base.replace("pure DEM, 300 spheres", f"pure DEM, {a.spheres} spheres")
    base = re.sub(r'(?m)^(pressure|confining_pressure) = "100 kPa"$',
                  lambda m: f'{m.group(1)} = "{a.pressure:g} kPa"', base)
    os.makedirs(a.out, exist_ok=True)
    series = []
    for seed in range(1, a.samples + 1):
        text = re.sub(r"(?m)^seed = 1$", f"seed = {seed}", base)
        loading = text.index("[dem.loading]")
        head, tail = text[:loading], text[loading:]
        tail = re.sub(r"(?m)^inertial_number = \S+", f"inertial_number = {a.inertial_number}", tail, 1)
        tail = re.sub(r"(?m)^axial_strain = \S+", f"axial_strain = {a.strain}", tail, 1)
        tail = re.sub(r"(?m)^lateral_tolerance = \S+", f"lateral_tolerance = {a.lateral_tolerance}", tail, 1)
        tail = re.sub(r"(?m)^every = \S+", "every = 25", tail, 1)
        job = os.path.join(a.out, f"seed{seed}.toml")
        open(job, "w").write(head + tail)
        run = os.path.join(a.out, f"seed{seed}")
        r = subprocess.run([a.exe, "dem", job, "--out", run, "--force"],
                           env=dict(os.environ, OMP_NUM_THREADS="1"), capture_output=True, text=True)
        status = "ok" if r.returncode == 0 else f"FAILED ({r.returncode}): {r.stderr.strip()[-300:]}"
        print(f"seed {seed}: {status}")
        if r.returncode == 0:
            series.append(os.path.join(run, "dem_series.csv"))
    if len(series) < a.samples:
        print(f"{a.samples - len(series)} sample(s) failed: the mean would not be the job's samples'",
              file=sys.stderr)
        return 1
    mean = a.mean or os.path.join(a.out, "mean.csv")
    return subprocess.call(tool_command("biaxial_seed_mean") + [mean] + series)


if __name__ == "__main__":
    sys.exit(main())
