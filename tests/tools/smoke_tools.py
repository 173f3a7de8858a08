#!/usr/bin/python3
"""Smoke runs of the tools of tools/mpmxdem_tools: each runs on a stored result (docs/data, tests/data), on a
run of the suite (a job's output directory under the build tree) or on a tiny input, and its exit
status and something it printed or wrote are checked.

Usage: /usr/bin/python3 tests/tools/smoke_tools.py SCRIPT [--exe MPMXDEM] [--bench BENCH_DEM]
           [--runs BUILD/tests/jobs]
SCRIPT: a tool's name (bench_sparing); one CTest test (tools.<script>.smoke) per tool.
Outputs go to a temporary directory, never into docs/. Exit 77 (skipped) where a Python package,
ParaView, a display or YADE is missing (the message says which), after what can be checked
without it.
"""
import argparse
import csv
import glob
import importlib.util
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TOOLS = os.path.join(ROOT, "tools")
LAUNCHER = os.path.join(TOOLS, "mpmxdem-tools")
DATA = os.path.join(ROOT, "docs", "data")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", OMP_NUM_THREADS="1", MPLBACKEND="Agg")


class Skip(Exception):
    pass


def need(*modules):
    for m in modules:
        if importlib.util.find_spec(m) is None:
            raise Skip(f"Python module {m} missing")


def need_yade():
    if shutil.which("yade") is None:
        raise Skip("yade missing (Debian package yade): the script runs inside yade")


def need_paraview():
    """The command prefix that runs a ParaView script here: [] with a display, xvfb-run without."""
    if importlib.util.find_spec("paraview") is None:
        raise Skip("ParaView's Python module missing (Debian package python3-paraview)")
    if os.environ.get("DISPLAY"):
        return []
    if shutil.which("xvfb-run") is None:
        raise Skip("no display and no xvfb-run (Debian package xvfb)")
    return ["xvfb-run", "-a"]


def tool(name, *args, rc=0, prefix=(), cwd=ROOT):
    """Runs `tools/mpmxdem-tools NAME ARGS`; fails unless it exits RC; returns its stdout and
    stderr."""
    cmd = list(prefix) + [sys.executable, LAUNCHER, name] + [str(a) for a in args]
    r = subprocess.run(cmd, cwd=cwd, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True)
    for attempt in range(3):
        if not (prefix and "bad X server connection" in r.stdout):
            break
        # xvfb-run -a on a loaded machine: ParaView found no usable X server (seen in a few of
        # about 50 renders on the 2-core VM, twice in a row once); the render is what is tested.
        print(f"$ {' '.join(cmd)}\n{r.stdout[-1500:]}\n(no usable X server: again)", flush=True)
        time.sleep(2 + 3 * attempt)
        r = subprocess.run(cmd, cwd=cwd, env=ENV, stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, text=True)
    print(f"$ {' '.join(cmd)}\n{r.stdout}", flush=True)
    if r.returncode != rc:
        sys.exit(f"FAILED: tools/mpmxdem-tools {name} exited {r.returncode}, expected {rc}")
    return r.stdout


def yade(name, *args):
    """Runs the YADE script NAME (tools/mpmxdem_tools/references/NAME.py) inside yade."""
    script = os.path.join(TOOLS, "mpmxdem_tools", "references", name + ".py")
    cmd = ["yade", "-j1", "-n", "-x", script] + [str(a) for a in args]
    r = subprocess.run(cmd, cwd=ROOT, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True)
    print(f"$ {' '.join(cmd)}\n{r.stdout[-4000:]}", flush=True)
    if r.returncode != 0:
        sys.exit(f"FAILED: {name} in yade exited {r.returncode}")
    return r.stdout


def check(cond, what):
    if not cond:
        sys.exit(f"FAILED: {what}")


def png(path):
    """PATH is a non-empty PNG file."""
    check(os.path.isfile(path), f"{path} was not written")
    with open(path, "rb") as f:
        check(f.read(8) == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG")


def rows(path):
    check(os.path.isfile(path), f"{path} was not written")
    with open(path, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def run_dir(o, name):
    d = os.path.join(o.runs, name)
    check(os.path.isfile(os.path.join(d, "results.h5")), f"{d}: no results.h5 (the run of the suite)")
    return d


# --- benchmarks: the smallest runs of the binaries --------------------------------------------
def bench_contact_laws(o, tmp):
    out = tool("bench_contact_laws", "--no-yade", "--rounds", 1, "--steps", 20, "--bench", o.bench)
    for law in ("CohFrict", "Hertz-Mindlin"):
        line = [x for x in out.splitlines() if x.startswith(f"| mpmxdem, {law} |")]
        check(len(line) == 1 and float(line[0].split("|")[2].split()[0]) > 0, f"no timing of {law}")


def bench_coupling(o, tmp):
    need("h5py", "numpy", "matplotlib")
    # The element scene (jobs/triaxial_mpmxdem_small.toml: 8 RVEs, about 1 s a run) with
    # dt_refresh 1 (the reference) and 5, one repetition on 2 ranks.
    tool("bench_coupling", "--exe", o.exe, "--out", tmp, "--scenes", "element",
         "--refresh", "1,5", "--reps", 1, "--np", 2)
    r = rows(os.path.join(tmp, "bench_coupling.csv"))
    check([x["variant"] for x in r] == ["dt_refresh = 1", "dt_refresh = 5"], "variants of the CSV")
    check(all(int(x["dem_steps"]) > 0 for x in r), "DEM steps counted")
    check(float(r[0]["q max"]) == 0.0 and float(r[1]["q max"]) < 0.05, "q errors against the reference")
    check("| element | dt_refresh = 5 |" in open(os.path.join(tmp, "bench_coupling.md")).read(), "the table")


def bench_dem_pairs(o, tmp):
    out = tool("bench_dem_pairs", o.bench, o.bench, "--steps", 20, "--reps", 1)
    check(out.count("old spheres 1000 threads 1") == 1 and "median ratio old/new" in out, "the pair's lines")


def bench_dem_speedup(o, tmp):
    out = tool("bench_dem_speedup", o.bench, "--steps", 5, "--reps", 1)
    check("medians: 1 thread" in out and "speed-ups " in out, "the medians line")


def bench_sparing(o, tmp):
    need("h5py", "numpy", "matplotlib")
    # Real runs: the element scene without sparing and with tolerance 1e-4 (about 1 s each).
    tool("bench_sparing", "--exe", o.exe, "--out", tmp, "--scenes", "element",
         "--tolerances", "0,1e-4", "--reps", 1, "--np", 2)
    r = rows(os.path.join(tmp, "bench_sparing.csv"))
    check(len(r) == 2 and float(r[0]["q max"]) == 0.0 and int(r[1]["dem_steps"]) <= int(r[0]["dem_steps"]),
          "the element scene's two rows")
    png(os.path.join(tmp, "bench_sparing.png"))
    # One table from earlier runs' stored CSVs.
    stored = ",".join(os.path.join(DATA, "sparing", f) for f in ("biaxial_4x8.csv", "footing_512.csv"))
    out = tool("bench_sparing", "--out", os.path.join(tmp, "stored"), "--from-csv", stored)
    check("| footing |" in out and "| biaxial |" in out, "rows of both stored scenes")
    png(os.path.join(tmp, "stored", "bench_sparing.png"))


def bench_speed_error(o, tmp):
    need("h5py", "numpy", "matplotlib")
    # One cell of the matrix: 125 spheres at I = 4e-3 to 1 %, pure DEM (the reference) and MPM x DEM
    # on one rank (about 3 s).
    md = os.path.join(tmp, "speed.md")
    with open(md, "w") as f:
        f.write("# page\n\nkept\n\n<!-- bench_speed_error:begin old -->\nold\n"
                "<!-- bench_speed_error:end -->\ntail\n")
    tool("bench_speed_error", "--sizes", 125, "--inertia", "4e-3", "--strain", 0.01, "--ranks", 1,
         "--exe", o.exe, "--work", os.path.join(tmp, "work"), "--markdown", md,
         "--figure", os.path.join(tmp, "pareto.png"))
    text = open(md).read()
    check(text.startswith("# page\n\nkept\n") and text.endswith("tail\n") and "\nold\n" not in text,
          "the generated part replaced between its markers")
    check("| DEM | 125 | 0.004 |" in text and "the reference |" in text, "the pure DEM row")
    mpm = [x for x in text.splitlines() if x.startswith("| MPMxDEM | 125 | 0.004 |")]
    check(len(mpm) == 1 and float(mpm[0].split("|")[6].split()[0]) < 20, "the MPM x DEM row's q error")
    png(os.path.join(tmp, "pareto.png"))


# --- the biaxial test: the suite's run of tests/jobs/biaxial_small.toml --------------------------
def biaxial_analysis(o, tmp):
    need("h5py", "numpy", "matplotlib")
    run = run_dir(o, "biaxial_small")
    out = tool("biaxial_analysis", run + ":small", "--dem",
               os.path.join(DATA, "biaxial_dem", "dem_series_300.csv"), "--figures", tmp)
    row = [x for x in out.splitlines() if x.startswith("| small | 2 x 4 | 32 |")]
    check(len(row) == 1, "the run's row (2 x 4 cells, 32 RVEs)")
    peak = float(row[0].split("|")[4].split()[0])
    check(5 < peak < 15, f"first peak ratio {peak}")
    for f in ("biaxial_stress_strain.png", "biaxial_strain_maps.png"):
        png(os.path.join(tmp, f))
    # --windows: the ratio's mean over the first window (the small run reaches a few % only)
    out = tool("biaxial_analysis", "--windows", run + ":small")
    row = [x for x in out.splitlines() if x.startswith("| small |")]
    check(len(row) == 1, "the run's --windows row")
    first = float(row[0].split("|")[2])
    check(1 < first < 15, f"mean ratio over 1-2 % {first}")


def biaxial_compare(o, tmp):
    need("h5py", "numpy", "matplotlib")
    run = run_dir(o, "biaxial_small")
    out = tool("biaxial_compare", "--dem", os.path.join(DATA, "biaxial_dem", "dem_series_300.csv"),
               run + ":small", "--strains", "0.0025,0.005,0.01")
    row = [x for x in out.splitlines() if x.startswith("| small |")]
    check(len(row) == 1, "the run's row")
    errors = [float(x) for x in row[0].split("|")[2:5]]
    check(all(abs(e) < 10 for e in errors), f"errors against the 300-sphere DEM {errors} %")


def biaxial_family(o, tmp):
    need("h5py", "numpy", "matplotlib")
    run = run_dir(o, "biaxial_small")
    # The same run twice: one family of two draws whose mean and range are the run's own figures.
    table = os.path.join(tmp, "family.csv")
    out = tool("biaxial_family", run + ":a", run + ":b", "--strains", "0.005,0.5", "--csv", table,
               "--dem", os.path.join(DATA, "biaxial_dem", "dem_series_300.csv"),
               "--figure", os.path.join(tmp, "family.png"))
    rows = [x for x in out.splitlines() if x.startswith("| a |") or x.startswith("| b |")]
    check(len(rows) == 2 and rows[0].split("|")[2:] == rows[1].split("|")[2:], "two identical run rows")
    peak = float(rows[0].split("|")[3].split()[0])
    check(rows[0].split("|")[5].strip() == "-", "no band past the run's end (50 %)")
    fam = [x for x in out.splitlines() if x.startswith("| 2 x 4 (")]
    check(len(fam) == 1, "one family row for the one mesh")
    cols = [c.strip() for c in fam[0].split("|")[1:-1]]
    check(cols[1] == "2", f"two draws: {cols[1]}")
    check(cols[2] == f"{peak:.2f} ({peak:.2f}-{peak:.2f})", f"the family's peak {cols[2]} against {peak}")
    png(os.path.join(tmp, "family.png"))
    # The manual's tables come from the CSV alone (standard library): the same family row.
    again = tool("biaxial_family", "--table", table)
    check(fam[0] in again.splitlines(), "--table prints the family row of the runs")


def biaxial_dem_seeds(o, tmp):
    need("numpy", "pandas")
    # Two samples of 100 spheres to 0.5 % at I = 4e-3 (about 1 s), then their mean.
    out = tool("biaxial_dem_seeds", tmp, "--samples", 2, "--spheres", 100, "--strain", 0.005,
               "--inertial-number", "4e-3", "--exe", o.exe)
    check("seed 1: ok" in out and "seed 2: ok" in out, "both samples ran")
    mean = rows(os.path.join(tmp, "mean.csv"))
    check(len(mean) >= 10 and all(float(r["sig_r"]) == 1e5 for r in mean), "the mean series")


def biaxial_j_maps(o, tmp):
    need("h5py", "numpy", "matplotlib")
    run = run_dir(o, "biaxial_small")
    out = tool("biaxial_j_maps", f"{run}:small:0.005", f"{run}:end:0.01",
               "--out", os.path.join(tmp, "j.png"))
    check("wrote" in out, "wrote the figure")
    png(os.path.join(tmp, "j.png"))


def render_run(o, tmp, script, run_name, *args):
    """A ParaView renderer of a run's points.xmf: its message for a missing run, then (where
    ParaView runs) a PNG of the suite's run RUN_NAME."""
    out = tool(script, os.path.join(tmp, "nothing"), os.path.join(tmp, "x.png"), rc=1)
    check("points.xmf is missing" in out, "the missing run's message")
    prefix = need_paraview()
    tool(script, run_dir(o, run_name), os.path.join(tmp, "r.png"), *args, prefix=prefix)
    png(os.path.join(tmp, "r.png"))


def biaxial_paraview(o, tmp):
    render_run(o, tmp, "biaxial_paraview", "biaxial_small", "--arrays", "q,z")


def biaxial_seed_mean(o, tmp):
    need("numpy", "pandas")
    seeds = [os.path.join(DATA, "biaxial_dem", f"dem_series_300_seed{k}.csv") for k in (2, 3)]
    out = tool("biaxial_seed_mean", os.path.join(tmp, "mean.csv"), *seeds)
    check("peak of the mean" in out, "the summary line")
    for r in rows(os.path.join(tmp, "mean.csv")):
        ratio = float(r["sig_a"]) / float(r["sig_r"])
        check(float(r["ratio_min"]) - 1e-9 <= ratio <= float(r["ratio_max"]) + 1e-9,
              f"mean ratio {ratio} between the samples' at eps_a {r['eps_a']}")


def coupling_bias(o, tmp):
    need("h5py", "numpy", "matplotlib")
    # Its statistics on stored runs (--reuse): the biaxial scene's runs take minutes, so each of the
    # four runs (two variants x offsets 0 and 3) is the suite's small biaxial run; identical
    # families: no spread, no difference.
    sys.path.insert(0, TOOLS)
    from mpmxdem_tools.bench import bench_coupling as bc
    from mpmxdem_tools.bench import coupling_bias as cb
    run = run_dir(o, "biaxial_small")
    old, speed = cb.SPEED["biaxial"]
    variants = ['end_forces = "separate"', 'end_forces = "carried"']
    for k in (0, 3):
        new = old.replace(speed, "%.10g" % (float(speed) * (1.0 + k * 1e-6)))
        pert = False if k == 0 else "%s=>%s" % (old, new)
        for v in variants:
            os.makedirs(os.path.join(tmp, "runs"), exist_ok=True)
            os.symlink(run, os.path.join(tmp, "runs", bc.run_name("biaxial", v, 0.0, 0, pert)))
    out = tool("coupling_bias", "--out", tmp, "--scene", "biaxial", "--offsets", "0,3", "--reuse",
               "--exe", o.exe)
    check(out.count("biaxial [end_forces") == 4, "four runs analysed")
    check(any(x.startswith("| pre-peak | 0.00 %, 0.00 % |") for x in out.splitlines()), "the pre-peak row")
    r = rows(os.path.join(tmp, "coupling_bias.csv"))
    check(len(r) > 10 and all(float(x["t"]) == 0.0 and x["mean_ref"] == x["mean_opt"] for x in r),
          "identical families: t = 0")


# --- the column collapse --------------------------------------------------------------------
def column_frictional_family(o, tmp):
    summary = os.path.join(DATA, "column_collapse_frictional", "summary.csv")
    out = tool("column_frictional_family", "--table", summary)
    n = len(rows(summary))
    check(sum(1 for x in out.splitlines() if x.startswith("| ") and " deg |" in x) == n,
          f"one table row per run of {summary} ({n})")


def column_resolution_figure(o, tmp):
    need("matplotlib", "pandas")
    out = tool("column_resolution_figure", "--data", DATA, "--fig", tmp)
    check("missing" not in out, "every series found in docs/data")
    png(os.path.join(tmp, "column_a2_resolution.png"))


def plot_column_collapse(o, tmp):
    need("matplotlib", "pandas", "numpy")
    # The loose N = 1000 runs, copied: the script writes DATA/summary.csv.
    data = os.path.join(tmp, "data")
    os.makedirs(data)
    for f in glob.glob(os.path.join(DATA, "column_collapse_yade", "a*_n1000_*.csv")):
        shutil.copy(f, data)
    out = tool("plot_column_collapse", "--data", data, "--fig", os.path.join(tmp, "fig"))
    check("fit runout_over_L0" in out, "the fitted exponents")
    check(len(rows(os.path.join(data, "summary.csv"))) == 3, "three summary rows")
    for f in ("column_profiles.png", "column_front.png", "column_runout_scaling.png"):
        png(os.path.join(tmp, "fig", f))


def render_column_collapse(o, tmp):
    render_run(o, tmp, "render_column_collapse", "column_collapse_tiny", "--times", "0,0.1")


def yade_column_collapse(o, tmp):
    need_yade()
    # 30 soft grains, a = 1, stopped at 0.2 t*.
    yade("yade_column_collapse", "--a", 1, "--n", 30, "--young", "3e6", "--tmax", 0.2,
         "--max-wall", 300, "--out", tmp, "--tag", "smoke")
    r = rows(os.path.join(tmp, "smoke_summary.csv"))
    check(len(r) == 1 and float(r[0]["H0_m"]) > 0, "the summary row")


def yade_column_collapse_partial(o, tmp):
    # A complete dense run's log and series: the partial summary agrees with the run's own.
    base = os.path.join(DATA, "column_collapse_yade", "dense_a1_n375_l0.05")
    out_csv = os.path.join(tmp, "partial.csv")
    out = tool("yade_column_collapse_partial", base + ".log", base + "_timeseries.csv", out_csv)
    check("dense_a1_n375_l0.05 to t/t* = 5.16" in out, "the printed line")
    got, want = rows(out_csv)[0], rows(base + "_summary.csv")[0]
    for key in ("N", "W_over_d50", "damping", "prep_steps", "collapse_steps"):
        check(float(got[key]) == float(want[key]), f"{key}: {got[key]} against the run's {want[key]}")
    for key in ("L0_m", "H0_m", "tstar_s", "L_f_m", "runout_over_L0", "Hf_over_H0", "t_end_over_tstar"):
        check(math.isclose(float(got[key]), float(want[key]), rel_tol=2e-3),
              f"{key}: {got[key]} against the run's {want[key]}")
    check(got["end_reason"].startswith("partial_"), "end_reason")


# --- the footing ------------------------------------------------------------------------------
def footing_sparing_map(o, tmp):
    need("h5py", "numpy", "matplotlib")
    run = os.path.join(run_dir(o, "footing_equilibrium/run"))
    out = tool("footing_sparing_map", run, run, "--out", os.path.join(tmp, "map.png"))
    check("128 RVEs;" in out and "spared share: median 0 %" in out, "the summary line (nothing spared)")
    png(os.path.join(tmp, "map.png"))


def rve_low_pressure_strength(o, tmp):
    # The stored tables (standard library only).
    out = tool("rve_low_pressure_strength", "--table")
    jobs = glob.glob(os.path.join(DATA, "column_collapse_rve_strength", "*.toml"))
    check(out.count("| seed ") == len(jobs), "one row per stored job")
    out = tool("rve_low_pressure_strength", "--table", "--dilatancy",
               "--data", os.path.join(DATA, "footing_rve_strength"))
    check("dilatancy angle at the peak" in out and out.count("| seed ") == 5, "the footing's table")
    # --run on one of the column's jobs cut to 16 % axial strain (about 1 s), then its table.
    data = os.path.join(tmp, "data")
    os.makedirs(data)
    text = open(os.path.join(DATA, "column_collapse_rve_strength", "n100_seed3.toml")).read()
    check("\naxial_strain = 0.30\n" in text, "the stored job's axial strain")
    with open(os.path.join(data, "n100_seed3.toml"), "w") as f:
        f.write(text.replace("\naxial_strain = 0.30\n", "\naxial_strain = 0.16\n")
                .replace("\nevery = 200\n", "\nevery = 50\n"))
    out = tool("rve_low_pressure_strength", "--data", data, "--exe", o.exe,
               "--run", os.path.join(tmp, "runs"))
    check("ran n100_seed3" in out, "the run")
    out = tool("rve_low_pressure_strength", "--data", data, "--table")
    row = [x for x in out.splitlines() if x.startswith("| seed 3 | 100 |")]
    check(len(row) == 1 and 20 < float(row[0].split("|")[3].split()[0]) < 90, "the run's peak angle")


# --- triaxial ---------------------------------------------------------------------------------
def dem_against_yade(o, tmp):
    ours = os.path.join(DATA, "yade_hertz_mindlin", "mpmxdem_dem_series.csv")
    theirs = os.path.join(ROOT, "tests", "data", "dem", "yade_triax_hertz_mindlin_N1000_I2.5e-4.csv")
    out = tool("dem_against_yade", ours, theirs)
    rms = [x for x in out.splitlines() if x.startswith("RMS of the relative q/p difference")]
    check(len(rms) == 1 and float(rms[0].split()[-2]) < 10, "the RMS line (a few %)")
    out = tool("dem_against_yade", ours, theirs, "--markdown")
    check(out.count("\n|") >= 5, "the markdown table")


def plot_triaxial(o, tmp):
    need("h5py", "numpy", "matplotlib")
    run = run_dir(o, "triaxial_mpmxdem_small")
    prefix = os.path.join(tmp, "tri")
    out = tool("plot_triaxial", "--out", prefix, "--run", run + "=small",
               "--csv", os.path.join(DATA, "triaxial_dem_8k", "dem_series.csv") + "=8k",
               "--csv", os.path.join(ROOT, "tests", "data", "dem", "yade_triax_N1000_I2.5e-4.csv") + "=yade",
               "--summary")
    check("RVE 7: lateral stress" in out, "the summary's eight RVEs")
    png(prefix + "_q_epsv.png")
    png(prefix + "_rves_0.png")


def render_points(o, tmp):
    render_run(o, tmp, "render_points", "triaxial_mpmxdem_small", "--arrays", "q")


def render_rve(o, tmp):
    out = tool("render_rve", "a.vtm", os.path.join(tmp, "x.png"), "--panels", "grains,forces", rc=1)
    check("unknown panel 'forces'" in out, "the unknown panel's message")
    out = tool("render_rve", os.path.join(tmp, "none.vtm"), os.path.join(tmp, "x.png"), rc=1)
    check("none_spheres.vtp is missing" in out, "the missing view's message")
    prefix = need_paraview()
    run = run_dir(o, "triaxial_mpmxdem_small")
    ckpt = sorted(glob.glob(os.path.join(run, "checkpoint_*.h5")))[-1]
    views = os.path.join(tmp, "views")
    subprocess.run([o.exe, "inspect", ckpt, "--rve", "0", "--vtk", views], check=True, env=ENV)
    vtm = sorted(glob.glob(os.path.join(views, "*.vtm")))
    check(vtm, "inspect --vtk wrote a view")
    tool("render_rve", vtm[0], os.path.join(tmp, "r.png"), "--size", "800x400", prefix=prefix)
    png(os.path.join(tmp, "r.png"))


def triaxial_errors(o, tmp):
    need("h5py", "numpy")
    run = run_dir(o, "triaxial_mpmxdem_small")
    out = tool("triaxial_errors", run + "=small", "--strain", 0.02)
    check("small (" in out and "reached eps_ax 2.0 %" in out, "the run reached 2 %")
    line = [x for x in out.splitlines() if "vs 30k DEM: q RMS" in x]
    check(len(line) == 1 and float(line[0].split("q RMS")[1].split()[0]) < 30, "the q error line")


def yade_triax_hertz_mindlin(o, tmp):
    need_yade()
    out = yade("yade_triax_hertz_mindlin", "--packing",
               os.path.join(ROOT, "jobs", "packings", "packing_N1000_hertz_mindlin.txt"), "--bench-steps", 20)
    check("us/particle-step" in out, "the timing line")


# --- YADE packings and the two-sphere reference -----------------------------------------------
def yade_export_packing(o, tmp):
    need_yade()
    out_txt, raw = os.path.join(tmp, "p.txt"), os.path.join(tmp, "raw.txt")
    yade("yade_export_packing", out_txt, 30, "--raw", raw)
    text = open(out_txt).read()
    check("# CELL" in text and "# CELL" not in open(raw).read(), "the cell added to the export only")
    spheres = [x for x in text.splitlines() if x.strip() and not x.startswith("#")]
    check(len(spheres) == 30, f"30 sphere lines, not {len(spheres)}")


def yade_read_packing(o, tmp):
    need_yade()
    out = yade("yade_read_packing", os.path.join(ROOT, "tests", "data", "dem", "yade_export_periodic.txt"))
    check("YADE read " in out, "the count line")


def yade_hertz_mindlin_pair(o, tmp):
    need_yade()
    out_csv = os.path.join(tmp, "pair.csv")
    yade("yade_hertz_mindlin_pair", out_csv)
    got, want = rows(out_csv), rows(os.path.join(ROOT, "tests", "data", "dem", "yade_hertz_mindlin_pair.csv"))
    check(len(got) == len(want), f"{len(got)} rows against the stored {len(want)}")
    for g, w in zip(got[::50], want[::50]):
        for k in ("Fn", "Fs_y", "Mb_z"):
            check(math.isclose(float(g[k]), float(w[k]), rel_tol=1e-6, abs_tol=1e-12),
                  f"step {g['step']}: {k} {g[k]} against the stored {w[k]}")


CASES = {f.__name__: f for f in (
    bench_contact_laws, bench_coupling, bench_dem_pairs, bench_dem_speedup, bench_sparing,
    bench_speed_error, biaxial_analysis, biaxial_compare, biaxial_dem_seeds, biaxial_family, biaxial_j_maps,
    biaxial_paraview, biaxial_seed_mean, column_frictional_family, column_resolution_figure,
    coupling_bias, dem_against_yade, footing_sparing_map, plot_column_collapse, plot_triaxial,
    render_column_collapse, render_points, render_rve, rve_low_pressure_strength, triaxial_errors,
    yade_column_collapse, yade_column_collapse_partial, yade_export_packing, yade_hertz_mindlin_pair,
    yade_read_packing, yade_triax_hertz_mindlin)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("script", choices=sorted(CASES))
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "mpmxdem"))
    ap.add_argument("--bench", default=os.path.join(ROOT, "build", "src", "dem", "bench_dem"))
    ap.add_argument("--runs", default=os.path.join(ROOT, "build", "tests", "jobs"),
                    help="the suite's job runs (BUILD/tests/jobs)")
    o = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="smoke_" + o.script + "_") as tmp:
        try:
            CASES[o.script](o, tmp)
        except Skip as e:
            print(f"SKIPPED: {o.script}: {e}")
            return 77
    print(f"{o.script}: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
