#!/usr/bin/python3
"""Speed against error of sparing idle RVEs (docs/design/sparing.md).

Runs each scene with dem.sparing.tolerance = 0 (the reference) and several tolerances, in pairs
alternating over the repetitions (the machine's load drifts), every run on the same number of
ranks with one thread per rank, niced; writes output.every = 1 so that the errors cover every
step (the footings keep their job's every 10th). The DEM steps come from the log's "work:" line
(checked against the rows' sum where a row is written every step). Per run: the DEM steps in
total, the spared fraction of the RVE steps, the loop's wall time and the critical rank's RVE
time (the `done:` line of the log), and the error of the scene's reference quantity against the
reference run:
  column   (jobs/geostatic_column_small.toml): base reaction (results.h5 /constraints/reaction,
           z of the first constraint) at the end and its largest deviation over the rows; point
           stresses: max over points and rows of max|sigma - sigma_ref| / p_ref (p_ref >= 1 kPa)
  element  (jobs/triaxial_mpmxdem_small.toml): q(eps_ax) of /means/q, max |q - q_ref| / max q_ref
  collapse (jobs/column_collapse_a0.5.toml, to rest): the runout of the connected deposit
           (L_f - L0) / L0 and the final height at the back wall H_f / H0
           (tools/mpmxdem_tools/analysis/mpm_column_collapse.py), differences relative to the reference run's;
           --noise: gravity changed by 1e-6
  footing  (jobs/footing_plane_strain.toml; _wide, _wider: the layer 2 and 3 times as wide and
           deep, tools/mpmxdem_tools/jobs/footing_make_job.py): the footing's reaction (z of /constraints/reaction
           "footing") against its settlement, relative to the reference's largest: at the end,
           the largest deviation, and the largest to 0.7 of the settlement; point stresses
           over max(p_ref, 50 kPa), median and 99th percentile. --noise adds the reference
           perturbed by 1e-6 (the footing's speed): the scene's own sensitivity
  biaxial  (docs/data/biaxial_in_turn/biaxial_plane_strain_4x8_in_turn.toml): the global stress ratio sigma_a / sigma_r
           (tools/mpmxdem_tools/analysis/biaxial_analysis.py: int sigma_zz dV over the specimen's height and area, over
           the 100 kPa confinement) against the log axial strain: max |ratio - ratio_ref| over
           the reference's peak ratio, before the reference's peak and after it, and the peak;
           --noise: the top platen's speed perturbed by 1e-6
Prints a markdown table (medians over the repetitions) and writes it, with a CSV and a figure of
DEM steps against error, to --out.

  tools/mpmxdem-tools bench_sparing --exe build/mpmxdem --out /tmp/bench_sparing [--reps 2] [--np 2]
      [--scenes column,column1000,element] [--tolerances 0,1e-6,1e-5,1e-4] [--max-spared 20]
  tools/mpmxdem-tools bench_sparing --out DIR --from-csv A/bench_sparing.csv,B/bench_sparing.csv
      (one table and figure from earlier runs' CSVs)
"""
import argparse
import csv
import os
import re
import statistics
import subprocess
import sys

import numpy as np

from .. import readers
from ..paths import ROOT

SCENES = {
    # name: (job, text replacements, reference quantity)
    "column": ("jobs/geostatic_column_small.toml", [], "column"),
    "column1000": ("jobs/geostatic_column_small.toml",
                   [("spheres = 100\n", "spheres = 1000\n"),
                    ('end_time = "0.2 s"', 'end_time = "0.4 s"')], "column"),
    "element": ("jobs/triaxial_mpmxdem_small.toml", [], "element"),
    # The column collapse a = 0.5 to rest (10 t*): the deposit idles for its last ~7 t*.
    "collapse": ("jobs/column_collapse_a0.5.toml", [], "collapse"),
    # The plane-strain biaxial on 4 x 8 cells to 10.5 %, its samples drawn in turn as when
    # docs/validation/speed.md measured it: the rough platens' dead zones and, after the peak, the
    # blocks outside the band load little.
    "biaxial": ("docs/data/biaxial_in_turn/biaxial_plane_strain_4x8_in_turn.toml", [], "biaxial"),
    # The strip footing (tools/mpmxdem_tools/jobs/footing_make_job.py): 512 RVEs on a 200 x 100 mm layer, and the
    # same footing on layers 2 and 3 times as wide and deep (2048 and 4608 RVEs), whose far field
    # idles more. Outputs every 10th step as the job (the work counts come from run_summary.json).
    "footing": ("jobs/footing_plane_strain.toml", [], "footing"),
    "footing_wide": (dict(width=0.4, depth=0.2), [], "footing"),
    "footing_wider": (dict(width=0.6, depth=0.3), [], "footing"),
}

# --noise: the reference run again with a perturbation far below any physical meaning, to
# measure how far the scene's own sensitivity (events that happen a few steps earlier or later)
# moves the reference quantity: the floor under which a sparing error means nothing.
PERTURBATION = {
    "footing": [('z = "-1 mm/s"', 'z = "-1.000001 mm/s"')],  # the footing's speed, 1e-6
    "biaxial": [('z = "-3.0 mm/s"', 'z = "-3.000003 mm/s"')],  # the top platen's speed, 1e-6
    "collapse": [('"-9.81 m/s^2"', '"-9.81001 m/s^2"')],  # gravity, 1e-6
}


def job_text(scene, tol, max_spared, perturbed=False):
    path, repl, kind = SCENES[scene]
    if isinstance(perturbed, str):  # "OLD=>NEW": a perturbation of the caller's own
        repl = repl + [tuple(perturbed.split("=>", 1))]
    elif perturbed:
        repl = repl + PERTURBATION[kind]
    if isinstance(path, dict):  # a footing written by tools/mpmxdem_tools/jobs/footing_make_job.py
        from ..jobs import footing_make_job  # noqa: E402 (a tool beside this one)
        text = footing_make_job.job_text(**dict(footing_make_job.DEFAULTS, **path))
    else:
        text = open(os.path.join(ROOT, path)).read()
    for a, b in repl:
        assert a in text, (scene, a)
        text = text.replace(a, b)
    if kind != "footing":  # errors over every step (the footings' rows are every 10th step)
        text = re.sub(r"^every = \d+", "every = 1", text, flags=re.M)
    text = text.replace("[dem.coupling]", "[dem.sparing]\ntolerance = %g\nmax_spared_steps = %d\n\n"
                        "[dem.coupling]" % (tol, max_spared), 1)
    # packings and other relative paths stay relative to the original job's directory
    return text


def run(args, scene, tol, max_spared, rep, perturbed=False):
    name = "%s_tol%g_max%d%s_rep%d" % (scene, tol, max_spared, "_perturbed" if perturbed else "", rep)
    job = os.path.join(args.out, "jobs", name + ".toml")
    out = os.path.join(args.out, "runs", name)
    os.makedirs(os.path.dirname(job), exist_ok=True)
    with open(job, "w") as f:
        f.write(job_text(scene, tol, max_spared, perturbed))
    summary = os.path.join(out, "run_summary.json")
    if args.reuse and os.path.exists(summary):
        return (out,) + read_summary(out)
    env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")
    cmd = ["nice", "-n", "5", "mpirun", "-n", str(args.np), args.exe, "run", job, "--out", out,
           "--force"]
    log = subprocess.run(cmd, env=env, cwd=ROOT, capture_output=True, text=True)
    if log.returncode != 0:
        sys.exit("run failed: %s\n%s" % (" ".join(cmd), log.stderr[-3000:]))
    return (out,) + read_summary(out)


def read_summary(run):
    """(loop wall [s], critical RVE time [s], work) from RUN/run_summary.json."""
    s = readers.summary(run)
    if s["ended"] != "end_time":
        sys.exit(f"{run}: the run ended by {s['ended']} {s['error']}")
    work = {"dem_steps": s["dem_steps"], "rve_steps": s["rve_steps"],
            "spared_steps": s["spared_rve_steps"]}
    return s["wall_s"], s["rve_time_critical_rank_s"], work


def measures(out, kind, work):
    with readers.results(out) as f:
        names = readers.constraint_names(f)
        d = {
            # the whole run's (run_summary.json), not only the written rows'
            "dem_steps": work["dem_steps"],
            "spared": work["spared_steps"] / max(work["rve_steps"], 1),
            "reaction": f["constraints/reaction"][:, names.index("footing") if kind == "footing"
                                                  else 0, 2].copy(),
            "settlement": f["constraints/displacement"][:, names.index("footing"), 2].copy()
            if kind == "footing" else None,
            "stress": f["points/stress"][:].copy(),
            "q": f["means/q"][:].copy(),
        }
        if f["rve/dem_steps"].shape[0] == f["step"].shape[0] and f["step"][-1] == f["step"].shape[0] - 1:
            # a row every step: the rows' DEM steps are the log's
            assert int(f["rve/dem_steps"][1:].sum()) == work["dem_steps"], out
    if kind == "biaxial":
        from ..analysis import biaxial_analysis  # noqa: E402 (a tool beside this one)
        r = biaxial_analysis.Run(out)
        d["eps"], d["ratio"] = r.eps.copy(), r.ratio.copy()
        r.f.close()
    if kind == "collapse":
        from ..analysis import mpm_column_collapse  # noqa: E402 (a tool beside this one)
        summ = mpm_column_collapse.analyse(out)["summ"]
        d["runout"] = summ["runout_connected_over_L0"]
        d["runout_all"] = summ["runout_over_L0"]
        d["height"] = summ["Hf_over_H0"]
    return d


def reaction_errors(r, r0):
    """A reaction's error against the reference's, over the rows after the start: at the end
    (relative to the reference's there) and the largest (relative to the reference's largest)."""
    return {"reaction end": abs(r[-1] - r0[-1]) / abs(r0[-1]),
            "reaction max": float(np.max(np.abs(r - r0)) / np.max(np.abs(r0)))}


def stress_error(s, s0, p_floor):
    """Per point and row: max |sigma - sigma_ref| over the components, over max(p_ref, p_floor)."""
    p0 = np.maximum(-(s0[..., 0] + s0[..., 4] + s0[..., 8]) / 3, p_floor)
    return np.abs(s - s0).max(axis=2) / p0


def errors(kind, m, ref):
    if kind == "biaxial":
        # The run's ratio at the reference's strains (the strains of a row differ slightly).
        ratio = np.interp(ref["eps"], m["eps"], m["ratio"])
        k = int(np.argmax(ref["ratio"]))
        e = np.abs(ratio - ref["ratio"]) / ref["ratio"][k]
        return {"pre-peak": float(e[:k + 1].max()), "post-peak": float(e[k:].max()),
                "peak": abs(m["ratio"].max() - ref["ratio"][k]) / ref["ratio"][k]}
    if kind == "collapse":
        return {"runout": abs(m["runout"] - ref["runout"]) / abs(ref["runout"]),
                "height": abs(m["height"] - ref["height"]) / abs(ref["height"])}
    if kind == "footing":
        # The footing's reaction at the reference's settlements (the same rows: the footing's
        # displacement is prescribed), relative to the reference's largest: at the end, the
        # largest deviation, and the largest over the first 70 % of the settlement (before the
        # load drops of RVEs by the footing's edge, whose timing a perturbation of 1e-6 moves:
        # --noise). Point stresses: max |sigma - sigma_ref| over the components, over
        # max(p_ref, the surcharge) (points beside the footing go to p = 0): median and 99th
        # percentile over points and rows.
        r, r0 = m["reaction"][1:], ref["reaction"][1:]
        u0 = np.abs(ref["settlement"][1:])
        early = u0 <= 0.7 * u0.max()
        e = stress_error(m["stress"], ref["stress"], 50e3)
        return dict(reaction_errors(r, r0),
                    **{"reaction early": float(np.max(np.abs(r - r0)[early]) / np.max(np.abs(r0))),
                       "stress median": float(np.median(e)),
                       "stress p99": float(np.percentile(e, 99))})
    if kind == "column":
        e = stress_error(m["stress"], ref["stress"], 1e3)
        return dict(reaction_errors(m["reaction"][1:], ref["reaction"][1:]),
                    **{"stress max": float(e.max()), "stress rms": float(np.sqrt((e ** 2).mean()))})
    q, q0 = m["q"], ref["q"]
    return {"q max": float(np.max(np.abs(q - q0)) / np.max(np.abs(q0)))}


def write_csv(path, rows):
    """The rows as a CSV whose columns are the union of the rows' keys, in first-seen order."""
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)


def error_text(r):
    """A table row's error of the scene's reference quantity, in words (rows of errors())."""
    if "q max" in r:
        return "q: %.2f %%" % (100 * r["q max"])
    if "pre-peak" in r:
        return "sigma_a/sigma_r: before the peak %.2f %%, after %.2f %%, peak %.2f %%" % (
            100 * r["pre-peak"], 100 * r["post-peak"], 100 * r["peak"])
    if "runout" in r:
        return "runout %.2f %%, H_f %.2f %%" % (100 * r["runout"], 100 * r["height"])
    if "stress median" in r:  # a footing
        return ("footing reaction %.2f %% at the end, max %.2f %% (to 0.7 of the settlement "
                "%.2f %%); point stress median %.2f %%, 99th percentile %.1f %%" % (
                    100 * r["reaction end"], 100 * r["reaction max"], 100 * r["reaction early"],
                    100 * r["stress median"], 100 * r["stress p99"]))
    return "reaction %.1e (max %.1e); stress max %.2f %%, rms %.2f %% of p" % (
        r["reaction end"], r["reaction max"], 100 * r["stress max"], 100 * r["stress rms"])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "mpmxdem"))
    ap.add_argument("--out", required=True)
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--reps", type=int, default=2)
    ap.add_argument("--scenes", default="column,column1000,element")
    ap.add_argument("--tolerances", default="0,1e-6,1e-5,1e-4")
    ap.add_argument("--max-spared", default="20", help="comma list; each tolerance > 0 with each")
    ap.add_argument("--from-csv", default="", help="comma list of earlier bench_sparing.csv")
    ap.add_argument("--reuse", action="store_true",
                    help="analyse the runs already in --out (their log.txt) instead of running them")
    ap.add_argument("--noise", action="store_true",
                    help="also the reference perturbed by 1e-6 (footing, biaxial and collapse scenes): the sensitivity floor")
    args = ap.parse_args()
    args.exe = os.path.abspath(args.exe)
    os.makedirs(args.out, exist_ok=True)
    tols = [float(t) for t in args.tolerances.split(",")]
    maxes = [int(x) for x in args.max_spared.split(",")]
    rows = []
    for path in filter(None, args.from_csv.split(",")):
        with open(path) as f:
            for r in csv.DictReader(f):
                rows.append({k: (v if k == "scene" else float(v)) for k, v in r.items() if v != ""})
    scenes = [] if args.from_csv else args.scenes.split(",")
    for scene in scenes:
        kind = SCENES[scene][2]
        variants = [(0.0, 20, False)] + [(t, mx, False) for t in tols if t > 0 for mx in maxes]
        if args.noise:
            variants.append((0.0, 20, True))
        res = {v: [] for v in variants}
        for rep in range(args.reps):
            for v in variants:  # alternating: every repetition runs every variant once
                out, wall, rve, work = run(args, scene, v[0], v[1], rep, v[2])
                res[v].append((out, wall, rve, work))
                print("%s tol %g max %d rep %d: wall %.2f s, RVE %.2f s" % (scene, v[0], v[1], rep,
                                                                            wall, rve), flush=True)
        ref = measures(res[variants[0]][0][0], kind, res[variants[0]][0][3])
        for v in variants:
            m = measures(res[v][0][0], kind, res[v][0][3])
            for other in res[v][1:]:  # every repetition gives the same bits: same DEM steps
                assert other[3]["dem_steps"] == m["dem_steps"]
            row = {"scene": scene, "tolerance": v[0], "max_spared_steps": v[1], "perturbed": int(v[2]),
                   "dem_steps": m["dem_steps"], "fewer": ref["dem_steps"] / max(m["dem_steps"], 1),
                   "spared": m["spared"],
                   "wall_s": statistics.median(x[1] for x in res[v]),
                   "rve_s": statistics.median(x[2] for x in res[v])}
            row.update(errors(kind, m, ref))
            rows.append(row)
    write_csv(os.path.join(args.out, "bench_sparing.csv"), rows)
    lines = ["| scene | tolerance | max spared | DEM steps | fewer | spared | loop wall [s] | "
             "RVE time [s] | error |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        err = error_text(r)
        lines.append("| %s | %s | %d | %d | %.1fx | %.0f %% | %.1f | %.1f | %s |" % (
            r["scene"], "0, perturbed 1e-6" if r.get("perturbed") else "%g" % r["tolerance"], r["max_spared_steps"], r["dem_steps"], r["fewer"],
            100 * r["spared"], r["wall_s"], r["rve_s"], err))
    table = "\n".join(lines)
    print(table)
    with open(os.path.join(args.out, "bench_sparing.md"), "w") as f:
        f.write(table + "\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6.5, 4))
        for scene in dict.fromkeys(r["scene"] for r in rows):
            rs = [r for r in rows if r["scene"] == scene and r["tolerance"] > 0
                  and r["max_spared_steps"] == 20]
            noise = [r for r in rows if r["scene"] == scene and r.get("perturbed")]
            if not rs:
                continue
            series = [("q max", "%s: q(eps)")] if "q max" in rs[0] else [
                ("pre-peak", "%s: stress ratio before the peak"),
                ("post-peak", "%s: stress ratio after the peak")] if "pre-peak" in rs[0] else [
                ("runout", "%s: runout"), ("height", "%s: final height")] if "runout" in rs[0] else [
                ("reaction max", "%s: footing reaction, max over the run"),
                ("reaction early", "%s: footing reaction to 0.7 of the settlement")
                ] if scene.startswith("footing") else [
                ("stress max", "%s: point stress, max"), ("reaction end", "%s: base reaction")]
            for key, label in series:
                e = [max(100 * r[key], 1e-4) for r in rs]
                line = ax.plot([r["fewer"] for r in rs], e, "o-", label=label % scene)[0]
                if noise:  # the scene's own sensitivity: a perturbation of 1e-6, nothing spared
                    ax.axhline(max(100 * noise[0][key], 1e-4), color=line.get_color(), ls="--", lw=0.8)
                for r, y in zip(rs, e):
                    ax.annotate("%g" % r["tolerance"], (r["fewer"], y), fontsize=7)
        ax.set_yscale("log")
        ax.axhline(2, color="grey", ls=":")
        ax.axvline(5, color="grey", ls=":")
        ax.set_xscale("log")
        ax.set_xlabel("DEM steps: reference / spared")
        ax.set_ylabel("error against sparing off [%]")
        ax.set_title("max_spared_steps 20; tolerance at each point", fontsize=9)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, "bench_sparing.png"), dpi=120)
    except ImportError:
        pass


if __name__ == "__main__":
    main()
