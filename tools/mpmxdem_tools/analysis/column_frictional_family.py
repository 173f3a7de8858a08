#!/usr/bin/python3
"""The a = 2 column as a Drucker-Prager continuum over friction angles and resolutions.

Writes variants of jobs/column_collapse_a2_frictional.toml (friction angle, points per cell, cell
size, mpm.free_density, the FLIP share of the transfer, the strain smoothing; the grid always
3 m x 1.5 m) under OUT, runs each on one rank (`mpiexec -n 1 build/mpmxdem run`), analyses it
with tools/mpmxdem_tools/analysis/mpm_column_collapse.py and writes OUT/summary.csv (one row per run: phi_deg, ppc,
cell_m, H_f/H0, runout of the farthest point and of the continuous deposit, kinetic energy at the
end, wall time) and OUT/<name>_timeseries.csv, OUT/<name>_profiles.csv.

Usage: tools/mpmxdem-tools column_frictional_family --out docs/data/column_collapse_frictional
       [--only NAME ...]   (about 60 min on one core, 45 of them for the 0.0156 m meshes;
                            --only reruns those and keeps the other rows of summary.csv)
       tools/mpmxdem-tools column_frictional_family --table docs/data/column_collapse_frictional/summary.csv
                           (prints the Markdown table of docs/validation/column_collapse.md)
"""
import argparse
import csv
import os
import re
import shutil
import subprocess
import time

from .column_grain_scale import deposit_measures, final_profile

from ..paths import ROOT, tool_command
BASE = os.path.join(ROOT, "jobs", "column_collapse_a2_frictional.toml")
L0, H0 = 0.5, 1.0  # the column of BASE [m]
# name: (phi [deg], points per cell along x and z, cell size [m], mpm.free_density, extra [mpm] keys)
RUNS = {
    "phi40_ppc1_h0.0625": (40, 1, 0.0625, "point", ""),
    "phi40_ppc2_h0.0625": (40, 2, 0.0625, "point", ""),
    "phi40_ppc3_h0.0625": (40, 3, 0.0625, "point", ""),
    "phi40_ppc4_h0.0625": (40, 4, 0.0625, "point", ""),
    "phi40_ppc2_h0.03125": (40, 2, 0.03125, "point", ""),
    "phi40_ppc2_h0.015625": (40, 2, 0.015625, "point", ""),
    "phi30_ppc2_h0.0625": (30, 2, 0.0625, "point", ""),
    "phi35_ppc2_h0.0625": (35, 2, 0.0625, "point", ""),
    "phi45_ppc2_h0.0625": (45, 2, 0.0625, "point", ""),
    "phi50_ppc2_h0.0625": (50, 2, 0.0625, "point", ""),
    "phi55_ppc2_h0.0625": (55, 2, 0.0625, "point", ""),
    "phi60_ppc2_h0.0625": (60, 2, 0.0625, "point", ""),
    "phi50_ppc2_h0.03125": (50, 2, 0.03125, "point", ""),
    "phi55_ppc2_h0.03125": (55, 2, 0.03125, "point", ""),
    "phi60_ppc4_h0.0625": (60, 4, 0.0625, "point", ""),
    "phi60_ppc2_h0.0625_flip0.99": (60, 2, 0.0625, "point", "flip = 0.99"),
    "phi60_ppc2_h0.0625_pic": (60, 2, 0.0625, "point", "flip = 0.0"),
    "phi40_ppc2_h0.0625_flip0.99": (40, 2, 0.0625, "point", "flip = 0.99"),
    "phi40_ppc2_h0.03125_flip0.99": (40, 2, 0.03125, "point", "flip = 0.99"),
    "phi40_ppc2_h0.015625_flip0.99": (40, 2, 0.015625, "point", "flip = 0.99"),
    "phi60_ppc2_h0.03125_flip0.99": (60, 2, 0.03125, "point", "flip = 0.99"),
    # the PIC share in time (mpm.pic_time = 0.02 t*, t* = sqrt(H0 / g) = 0.319 s): the same filter
    # of the transfer's noise on every mesh
    "phi40_ppc2_h0.0625_pic0.02": (40, 2, 0.0625, "point", 'pic_time = "6.4 ms"'),
    "phi40_ppc2_h0.03125_pic0.02": (40, 2, 0.03125, "point", 'pic_time = "6.4 ms"'),
    "phi40_ppc2_h0.015625_pic0.02": (40, 2, 0.015625, "point", 'pic_time = "6.4 ms"'),
    # the cell's volume-averaged velocity gradient for every point of it (mpm.strain_smoothing):
    # no point of a cell dilates while its neighbours compact
    "phi40_ppc2_h0.0625_smoothed": (40, 2, 0.0625, "point", 'strain_smoothing = "cell"'),
    "phi40_ppc2_h0.03125_smoothed": (40, 2, 0.03125, "point", 'strain_smoothing = "cell"'),
    "phi40_ppc2_h0.015625_smoothed": (40, 2, 0.015625, "point", 'strain_smoothing = "cell"'),
    "phi40_ppc2_h0.0625_grid": (40, 2, 0.0625, "grid", ""),
    "phi40_ppc2_h0.03125_grid": (40, 2, 0.03125, "grid", ""),
    "phi40_ppc2_h0.015625_grid": (40, 2, 0.015625, "grid", ""),
}


def variant(phi, ppc, h, free_density="point", extra=""):
    text = open(BASE).read()
    if free_density != "point":
        text = re.sub(r'^\[mpm\]$', f'[mpm]\nfree_density = "{free_density}"', text, count=1,
                      flags=re.M)
    if extra:
        text = re.sub(r'^\[mpm\]$', f'[mpm]\n{extra}', text, count=1, flags=re.M)
    text = re.sub(r'^friction_angle = .*$', f'friction_angle = "{phi} deg"', text, count=1,
                  flags=re.M)
    text = re.sub(r'^points_per_cell = .*$', f"points_per_cell = [{ppc}, 1, {ppc}]", text,
                  count=1, flags=re.M)
    text = re.sub(r'^spacing = .*$', f"spacing = [{h}, 0.0625, {h}]", text, count=1, flags=re.M)
    text = re.sub(r'^cells = .*$', f"cells = [{round(3.0 / h)}, 1, {round(1.5 / h)}]", text,
                  count=1, flags=re.M)
    return text


def table(summary):
    """The Markdown table of a summary.csv, in the order of RUNS; the deposit's runout to 0.05 H0
    and centre of mass (column_grain_scale.deposit_measures) from the profiles beside it."""
    folder = os.path.dirname(summary)
    rows = {r["name"]: r for r in csv.DictReader(open(summary))}
    out = ["| phi | points per cell | cell (L0 / n) | stress-free points dilate | transfer | strain | H_f/H0 | "
           "runout, farthest point | runout, continuous deposit | runout to h < 0.05 H0 | centre of mass x / L0 |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    dilate = {"point": "freely", "grid": "up to the material around"}
    transfer = {"": "FLIP", "flip = 0.99": "FLIP 0.99", "flip = 0.0": "PIC",
                'pic_time = "6.4 ms"': "PIC in 0.02 t*"}
    strain = {"": "per point", 'strain_smoothing = "cell"': "cell mean"}
    for name, (phi, ppc, h, fd, extra) in RUNS.items():
        if name not in rows:
            continue
        r = rows[name]
        head = (f"| {phi} deg | {'1' if ppc == 1 else f'{ppc} x {ppc}'} | L0/{round(0.5 / h)} | {dilate[fd]} | "
                f"{transfer.get(extra, 'FLIP')} | {strain.get(extra, 'per point')} |")
        if r["exit"] != "0":
            out.append(f"{head} exit {r['exit']} | | | | |")
            continue
        r5, _, xc, _ = deposit_measures(*final_profile(os.path.join(folder, f"{name}_profiles.csv")), L0, H0)
        out.append(f"{head} {float(r['Hf_over_H0']):.3f} | {float(r['runout_over_L0']):.2f} | "
                   f"{float(r['runout_connected_over_L0']):.2f} | {r5:.2f} | {xc:.2f} |")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out")
    ap.add_argument("--table", metavar="SUMMARY_CSV")
    ap.add_argument("--only", nargs="*", default=None)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "mpmxdem"))
    args = ap.parse_args()
    if args.table:
        print(table(args.table))
        return
    if not args.out:
        ap.error("--out or --table is required")
    os.makedirs(args.out, exist_ok=True)
    env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    rows = []
    for name, (phi, ppc, h, fd, extra) in RUNS.items():
        if args.only and name not in args.only:
            continue
        work = os.path.join(args.out, "runs", name)
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(work)
        job = os.path.join(work, "job_in.toml")
        open(job, "w").write(variant(phi, ppc, h, fd, extra))
        t0 = time.time()
        rc = subprocess.run(["mpiexec", "-n", "1", "--bind-to", "none", args.exe, "run", job,
                             "--out", os.path.join(work, "run")], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
        wall = time.time() - t0
        row = {"name": name, "phi_deg": phi, "ppc": ppc, "cell_m": h, "exit": rc,
               "wall_s": round(wall, 1)}
        if rc == 0:
            data = os.path.join(work, "data")
            subprocess.run(tool_command("mpm_column_collapse")
                           + [os.path.join(work, "run"), "--data", data, "--fig", data],
                           stdout=subprocess.DEVNULL, check=True)
            summary = next(csv.DictReader(open(os.path.join(data, "summary.csv"))))
            for k in ("Hf_over_H0", "runout_over_L0", "runout_connected_over_L0",
                      "Ekend_over_MgH0"):
                row[k] = summary[k]
            for kind in ("timeseries", "profiles"):
                shutil.copy(os.path.join(data, f"a2_{kind}.csv"),
                            os.path.join(args.out, f"{name}_{kind}.csv"))
        print(row, flush=True)
        rows.append(row)
        shutil.rmtree(work, ignore_errors=True)
    keys = ["name", "phi_deg", "ppc", "cell_m", "exit", "Hf_over_H0", "runout_over_L0",
            "runout_connected_over_L0", "Ekend_over_MgH0", "wall_s"]
    # --only keeps the rows of the runs it did not make.
    path = os.path.join(args.out, "summary.csv")
    if args.only and os.path.exists(path):
        made = {r["name"] for r in rows}
        rows = [r for r in csv.DictReader(open(path)) if r["name"] not in made] + rows
        rows.sort(key=lambda r: list(RUNS).index(r["name"]) if r["name"] in RUNS else len(RUNS))
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in keys})


if __name__ == "__main__":
    main()
