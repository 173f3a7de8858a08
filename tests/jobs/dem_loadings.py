#!/usr/bin/python3
"""jobs.dem.loadings: `mpmxdem dem` with the two loadings other than the triaxial test.

jobs/triaxial_dem_small.toml (300 spheres prepared at 100 kPa) with its [dem.loading] replaced:
- isotropic to 150 kPa: the last row's p within dem.preparation.stress_tolerance (1 %) of it;
- strain_path, L = [[0, 5, 0], [0, 0, 0], [0, 0, -5]] 1/s for 2 ms: the loading lasts 2 ms (to one
  DEM step) and the axial strain eps_a = -int L_zz dt = 0.01 (to 1e-3 of it: one step's share).
Each ends with exit 0 and both packings written. Standard library only.

Usage: dem_loadings.py MPMXDEM WORKDIR
"""
import csv
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LOADINGS = {
    "isotropic": 'type = "isotropic"\nconfining_pressure = "150 kPa"\ninertial_number = 1e-2\n',
    "strain_path": 'type = "strain_path"\n'
                   'velocity_gradient = [0.0, 5.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -5.0]\n'
                   'duration = "0.002 s"\n',
}


def run(exe, work, name):
    """Writes the job, runs `mpmxdem dem` on it; the series' rows as dicts of floats."""
    src = open(os.path.join(ROOT, "jobs", "triaxial_dem_small.toml")).read()
    i, j = src.index("[dem.loading]"), src.index("[output]")
    job = os.path.join(work, name + ".toml")
    with open(job, "w") as f:
        f.write(src[:i] + "[dem.loading]\n" + LOADINGS[name] + "\n" + src[j:])
    out = os.path.join(work, name)
    done = subprocess.run([exe, "dem", job, "--out", out, "--force"], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{name}: exit {done.returncode}\n{done.stderr[-3000:]}")
    for f in ("prepared_packing.txt", "final_packing.txt", "dem_series.csv"):
        if not os.path.isfile(os.path.join(out, f)):
            sys.exit(f"{name}: no {f}")
    with open(os.path.join(out, "dem_series.csv")) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def main():
    exe, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    failures = []
    rows = run(exe, work, "isotropic")
    p = rows[-1]["p"]
    print(f"isotropic: p = {p:.1f} Pa after {rows[-1]['iter'] - rows[0]['iter']:.0f} steps (target 150000)")
    if abs(p / 150e3 - 1.0) > 0.01:
        failures.append(f"isotropic: p = {p} Pa, not within 1 % of 150 kPa")
    rows = run(exe, work, "strain_path")
    lasted, dt, eps_a = rows[-1]["time"] - rows[0]["time"], rows[-1]["dt"], rows[-1]["eps_a"]
    print(f"strain_path: {len(rows)} rows, lasted {lasted:.6g} s (2 ms), eps_a = {eps_a:.6g} (0.01)")
    if abs(lasted - 0.002) > 1.5 * dt:
        failures.append(f"strain_path: lasted {lasted} s, not 0.002 s to one step ({dt} s)")
    if abs(eps_a / 0.01 - 1.0) > 1e-3:
        failures.append(f"strain_path: eps_a = {eps_a}, not 0.01 to 1e-3")
    if failures:
        sys.exit("\n".join(failures))
    print("both loadings as asked")


if __name__ == "__main__":
    main()
