#!/usr/bin/python3
"""Speed against error: the paper's drained triaxial test over a matrix of RVE sizes and inertial
numbers, in MPM x DEM (the paper's single cell, 8 RVEs) and in pure DEM (one sample of the same
size), every result compared with one reference curve. Writes a Markdown table into
docs/validation/speed.md (between generated-part markers) and a Pareto plot of time against error.

Usage (Debian's python3-matplotlib and python3-h5py; use /usr/bin/python3), from the repository:
  tools/mpmxdem-tools bench_speed_error [--sizes 125,250,500,1000] [--inertia 2.5e-4,1e-3,4e-3]
      [--strain 0.25] [--ranks 2] [--budget-s 400] [--work DIR] [--reuse N:I=RUN_DIR]...
      [--reference CSV] [--markdown docs/validation/speed.md] [--figure docs/figures/pareto.png]

Every size N gets one sample: N = 1000 is the reference packing of ../shared/reference
(jobs/packings/packing_N1000_e0.562.txt), the others are generated clouds with the same size
distribution (seed 1). The sample is prepared (compacted to 100 kPa) once, by the first pure DEM
run of that size; the MPM x DEM runs of that size load the prepared packing.

Reduced cost: an MPM x DEM run whose estimated wall time (from the measured cost of the cheapest
cell, scaled by N / I) exceeds --budget-s is run for a few hundred MPM steps only; its time is
extrapolated from the measured per-step cost, and its errors come from a full earlier run given
with --reuse N:I=DIR (e.g. the output of jobs/triaxial_mpmxdem.toml for 1000:2.5e-4), or are left
blank. The table says which rows are extrapolated.

Errors against the reference (default: the pure DEM run of the largest N at the smallest I; or
--reference, a series with columns eps_a, eps_v, q such as a 30,000-sphere `mpmxdem dem` run):
RMS relative error of q over eps_ax in [0.2 %, --strain], relative error of the peak q, and the
difference of eps_v at --strain (percentage points). Strains are logarithmic (compression
positive); MPM x DEM means are converted as in tools/mpmxdem_tools/analysis/plot_triaxial.py.
"""
import argparse
import math
import os
import platform
import re
import shutil
import subprocess
import sys
import time

import numpy as np

from ..analysis.plot_triaxial import read_csv, series_of_csv, series_of_run  # noqa: E402

from .. import readers
from ..paths import ROOT as REPO

REF_PACKING = os.path.join(REPO, "jobs", "packings", "packing_N1000_e0.562.txt")
RHO_S = 2650.0  # grain density [kg/m^3]
P0 = 1e5  # confining pressure [Pa]
EPS_LO = 0.002  # errors of q from 0.2 % axial strain (q ~ 0 before: relative errors undefined)

MATERIAL = """[dem.material]
density = "2650 kg/m^3"
young_modulus = "300 MPa"
stiffness_ratio = 0.5
friction_angle = "30 deg"
rolling_stiffness = 2.0
rolling_strength = 0.3
"""
PREPARATION = """[dem.preparation]
pressure = "100 kPa"
friction_angle = "1 deg"
"""


def sample_section(n, packing):
    if packing:
        return f'[dem.sample]\npacking = "{packing}"\n'
    return (f"[dem.sample]\nspheres = {n}\npsd_diameters = [\"130 um\", \"270 um\"]\n"
            "psd_passing = [0.0, 1.0]\nseed = 1\n")


def dem_job(n, inertia, strain, packing):
    return (f'title = "bench_speed_error: pure DEM, N = {n}, I = {inertia}"\n' + MATERIAL +
            sample_section(n, packing) + PREPARATION +
            f'[dem.loading]\ntype = "triaxial"\ninertial_number = {inertia}\naxial_strain = {strain}\n'
            'confining_pressure = "100 kPa"\n[output]\nevery = 200\n')


def platen_velocity(inertia):
    return inertia * math.sqrt(P0 / RHO_S)  # eq. 13 [m/s]


def mpm_job(n, inertia, strain, packing, shape):
    v = platen_velocity(inertia)
    end_time = strain / v  # the fixed 1 m cell: log strain V t / h
    faces = "".join(f'[[mpm.traction]]\nface = "{f}"\npressure = "100 kPa"\n' for f in ("x-", "x+", "y-", "y+"))
    return (f'title = "bench_speed_error: MPM x DEM, 8 RVEs of N = {n}, I = {inertia}"\n' + MATERIAL +
            sample_section(n, packing) + PREPARATION +
            f"[dem.coupling]\ninertial_number = {inertia}\n"
            f'[mpm]\nshape_function = "{shape}"\nupdate = "usf"\nflip = 1.0\nmove_points = false\n'
            f'damping = 0.2\nend_time = "{end_time:.9g} s"\n'
            "[mpm.grid]\norigin = [0.0, 0.0, 0.0]\nspacing = [1.0, 1.0, 1.0]\ncells = [1, 1, 1]\n"
            '[[mpm.body]]\nmin = [0.0, 0.0, 0.0]\nmax = [1.0, 1.0, 1.0]\npoints_per_cell = 2\n'
            'density = "1696 kg/m^3"\nmaterial = "dem"\n'
            '[[mpm.velocity]]\nface = "z-"\nz = 0.0\n'
            f'[[mpm.velocity]]\nface = "z+"\nz = "{-v * 1e3:.9g} mm/s"\n' + faces +
            '[output]\nevery = 20\nprogress_interval = "60 s"\ncheckpoint_interval = "10 h"\n')


def mpirun_env():
    env = dict(os.environ)
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    env.pop("OMP_NUM_THREADS", None)
    return env


def run(cmd, env, log):
    t0 = time.monotonic()
    with open(log, "w") as f:
        rc = subprocess.call(cmd, stdout=f, stderr=subprocess.STDOUT, env=env)
    if rc != 0:
        sys.exit(f"bench_speed_error: {' '.join(cmd)} failed (exit {rc}); see {log}")
    return time.monotonic() - t0


def run_dem(exe, work, n, inertia, strain, packing):
    d = os.path.join(work, f"dem_N{n}_I{inertia}")
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(work, exist_ok=True)
    job = d + ".toml"
    with open(job, "w") as f:
        f.write(dem_job(n, inertia, strain, packing))
    env = mpirun_env()
    env["OMP_NUM_THREADS"] = "1"
    run([exe, "dem", job, "--out", d], env, d + ".log")
    series = read_csv(os.path.join(d, "dem_series.csv"))
    return d, float(series["wall_s"][-1])  # loading wall time, preparation excluded


def mpm_done(run_dir):
    """(MPM steps, time [s], loop wall [s]) of a run, from its run_summary.json."""
    s = readers.summary(run_dir)
    return s["mpm_steps"], s["time_s"], s["wall_s"]


def run_mpm(exe, work, n, inertia, strain, packing, shape, ranks, max_steps=None):
    d = os.path.join(work, f"mpm_N{n}_I{inertia}_{shape}" + ("_partial" if max_steps else ""))
    shutil.rmtree(d, ignore_errors=True)
    job = d + ".toml"
    with open(job, "w") as f:
        f.write(mpm_job(n, inertia, strain, packing, shape))
    cmd = ["mpiexec", "-n", str(ranks), "--bind-to", "none", exe, "run", job, "--out", d]
    if max_steps:
        cmd += ["--max-steps", str(max_steps)]
    run(cmd, mpirun_env(), d + ".log")
    steps, t, wall = mpm_done(d)
    return d, steps, t, wall


def errors(series, ref, strain):
    eps, epsv, q = series
    reps, repsv, rq = ref
    if eps[-1] < strain * 0.999:
        return None
    grid = reps[(reps >= EPS_LO) & (reps <= strain)]
    qi = np.interp(grid, eps, q)
    qr = np.interp(grid, reps, rq)
    rms = math.sqrt(np.mean(((qi - qr) / qr) ** 2))
    def peak_q(e, qq):  # largest q up to `strain`, the value at `strain` included
        return max(qq[e <= strain].max(initial=-np.inf), np.interp(strain, e, qq))

    peak = peak_q(eps, q) / peak_q(reps, rq) - 1.0
    dv = np.interp(strain, eps, epsv) - np.interp(strain, reps, repsv)
    return rms, peak, dv


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", default="125,250,500,1000")
    ap.add_argument("--inertia", default="2.5e-4,1e-3,4e-3")
    ap.add_argument("--strain", type=float, default=0.25)
    ap.add_argument("--shape", default="linear", help="MPM shape function of the coupled runs")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--budget-s", type=float, default=400.0, help="longest MPM x DEM run done in full")
    ap.add_argument("--work", default=os.path.join(REPO, "results", "bench_speed_error"))
    ap.add_argument("--exe", default=os.path.join(REPO, "build", "mpmxdem"))
    ap.add_argument("--reuse", action="append", default=[], help="N:I=DIR of a full MPM x DEM run")
    ap.add_argument("--reference", help="reference series CSV (eps_a, eps_v, q)")
    ap.add_argument("--markdown", default=os.path.join(REPO, "docs", "validation", "speed.md"))
    ap.add_argument("--figure", default=os.path.join(REPO, "docs", "figures", "pareto.png"))
    a = ap.parse_args()
    sizes = sorted(int(s) for s in a.sizes.split(","))
    inertias = sorted(float(s) for s in a.inertia.split(","))
    reuse = {}
    for r in a.reuse:
        key, _, path = r.partition("=")
        n, _, i = key.partition(":")
        reuse[(int(n), float(i))] = path

    rows = []  # (method, n, inertia, wall, core_s, series or None, note)
    packings = {}
    for n in sizes:  # pure DEM first: it prepares the sample of each size
        for inertia in inertias:
            packing = REF_PACKING if n == 1000 else packings.get(n)
            d, wall = run_dem(a.exe, a.work, n, inertia, a.strain, packing)
            packings.setdefault(n, REF_PACKING if n == 1000 else os.path.join(d, "prepared_packing.txt"))
            rows.append(("DEM", n, inertia, wall, wall, series_of_csv(os.path.join(d, "dem_series.csv"), q_column=True), ""))
            print(f"pure DEM   N = {n:5d} I = {inertia:g}: {wall:8.1f} s", flush=True)
    per_unit = None  # MPM x DEM wall seconds per (N / I), from the cells run so far
    for n in sizes:
        for inertia in inertias:
            est = per_unit * n / inertia if per_unit else 0.0
            packing = packings[n]
            if est <= a.budget_s:
                d, steps, t, wall = run_mpm(a.exe, a.work, n, inertia, a.strain, packing, a.shape, a.ranks)
                note = ""
                series = series_of_run(d, von_mises_mean=True)
            else:
                end_time = a.strain / platen_velocity(inertia)
                d, steps, t, wall = run_mpm(a.exe, a.work, n, inertia, a.strain, packing, a.shape, a.ranks,
                                            max_steps=600)
                wall = wall / steps * (steps * end_time / t)  # per-step cost times the steps to the end
                src = reuse.get((n, inertia))
                series = series_of_run(src, von_mises_mean=True) if src else None
                note = (f"time extrapolated from {steps} MPM steps" +
                        (f"; errors from the full run {os.path.relpath(src, REPO)}" if src else "; errors not measured"))
            per_unit = max(per_unit or 0.0, wall * inertia / n)
            rows.append(("MPMxDEM", n, inertia, wall, wall * a.ranks, series, note))
            print(f"MPM x DEM  N = {n:5d} I = {inertia:g}: {wall:8.1f} s {note}", flush=True)

    if a.reference:
        ref, ref_label = series_of_csv(a.reference, q_column=True), os.path.relpath(os.path.abspath(a.reference), REPO)
    else:
        ref = next(r[5] for r in rows if r[0] == "DEM" and r[1] == sizes[-1] and r[2] == inertias[0])
        ref_label = f"pure DEM, N = {sizes[-1]}, I = {inertias[0]:g} (this matrix)"
    table = []
    for method, n, inertia, wall, core_s, series, note in rows:
        e = errors(series, ref, a.strain) if series is not None else None
        if series is ref:
            note = "the reference"
        table.append((method, n, inertia, wall, core_s, e, note))
    write_markdown(a, table, ref_label)
    plot_pareto(a, table, ref_label)


def write_markdown(a, table, ref_label):
    cpu = platform.processor() or platform.machine()
    lines = [
        "<!-- bench_speed_error:begin (generated by tools/mpmxdem_tools/bench/bench_speed_error.py; edit outside the markers) -->",
        f"Generated {time.strftime('%Y-%m-%d %H:%M')} on {os.cpu_count()} cores ({cpu}) by:",
        "",
        "    " + " ".join(["tools/mpmxdem-tools bench_speed_error"] + sys.argv[1:]),
        "",
        f"Drained triaxial to eps_ax = {a.strain:g} (log strain), 100 kPa lateral. MPM x DEM: the paper's",
        f"single cell with 8 RVEs ({a.shape} shape functions, fixed points), {a.ranks} ranks x 1 thread;",
        "pure DEM: one sample, 1 thread. Wall = loading only (sample preparation excluded).",
        f"Reference: {ref_label}. Errors: RMS relative error of q over eps_ax in [0.2 %, {100 * a.strain:g} %],",
        "relative error of the peak q, eps_v at the end minus the reference's (percentage points).",
        "",
        "| method | N | I | wall [s] | core-s | RMS err q | peak q err | d eps_v [pt] | note |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---|",
    ]
    for method, n, inertia, wall, core_s, e, note in table:
        err = (f"{100 * e[0]:.1f} % | {100 * e[1]:+.1f} % | {100 * e[2]:+.2f}" if e else "- | - | -")
        lines.append(f"| {method} | {n} | {inertia:g} | {wall:.1f} | {core_s:.1f} | {err} | {note} |")
    lines += ["", f"![time against error]({os.path.relpath(a.figure, os.path.dirname(a.markdown))})",
              "<!-- bench_speed_error:end -->"]
    block = "\n".join(lines) + "\n"
    text = ""
    if os.path.exists(a.markdown):
        with open(a.markdown) as f:
            text = f.read()
    m = re.search(r"<!-- bench_speed_error:begin.*?<!-- bench_speed_error:end -->\n?", text, re.S)
    text = text[:m.start()] + block + text[m.end():] if m else (text or "# Benchmarks\n\n") + block
    tmp = a.markdown + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, a.markdown)
    print("wrote", a.markdown)


def plot_pareto(a, table, ref_label):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    for method, marker in (("MPMxDEM", "o"), ("DEM", "s")):
        pts = [(c, 100 * e[0], n, i) for m, n, i, w, c, e, note in table if m == method and e]
        if not pts:
            continue
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], marker=marker, label=method)
        for c, err, n, i in pts:
            ax.annotate(f"{n}/{i:g}", (c, err), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_xlabel("core-seconds (loading)")
    ax.set_ylabel("RMS relative error of q [%]")
    ax.set_title(f"time against error (labels N/I); reference: {ref_label}", fontsize=8)
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    os.makedirs(os.path.dirname(a.figure), exist_ok=True)
    fig.savefig(a.figure, dpi=120)
    print("wrote", a.figure)


if __name__ == "__main__":
    sys.exit(main())
