#!/usr/bin/python3
"""Speed against error of the RVE step's work-saving options (docs/design/dem.md "RVE step"):
dem.coupling.dt_refresh (the critical time step kept over several DEM steps) and
dem.coupling.end_forces = "carried" (one force evaluation fewer per RVE step).

Runs each scene of tools/mpmxdem_tools/bench/bench_sparing.py with each variant of its [dem.coupling] table (the
first is the reference; a variant is one or more lines joined with '+', e.g.
'dt_refresh = 20+end_forces = "carried"'), in repetitions that
alternate the variants (the machine's load drifts), every run on --np ranks with one thread per
rank, niced. Per variant: the DEM steps (the run's run_summary.json), the medians of the loop's wall
time and of the critical rank's RVE time, their ratios to the reference's (medians of the
per-repetition ratios: each repetition runs every variant within a few minutes), and the error
of the scene's reference quantity against the reference run (bench_sparing's measures: footing
reaction and point stresses, collapse runout and height, biaxial stress ratio, element q(eps),
column base reaction and point stresses). --noise adds the reference perturbed by 1e-6
(footing, biaxial and collapse scenes): the scene's own sensitivity, under which an error means nothing.
--perturb 'OLD=>NEW' (repeatable) adds the reference with a replacement of one's own (more
samples of that sensitivity). --tolerance runs every variant with sparing on (dem.sparing.tolerance) instead of off; a variant's
part 'sparing.tolerance = x' sets it for that variant alone, a part 'numerics.KEY = x' sets
dem.numerics.KEY (e.g. 'numerics.verlet_skin_min = 0.03': the adaptive Verlet skin).

  tools/mpmxdem-tools bench_coupling --out /tmp/bench_dt [--scenes footing] [--refresh 1,5,20,100]
      [--variants 'dt_refresh = 1;end_forces = "carried"'] [--reps 3] [--np 2] [--tolerance 0]
      [--noise]
--refresh 1,5 is short for --variants 'dt_refresh = 1;dt_refresh = 5'. Prints a markdown table
and writes it with a CSV (bench_coupling.csv) to --out.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys

from .. import readers
from . import bench_sparing as bs  # noqa: E402 (a tool beside this one: scenes, measures, errors)


def slug(variant):
    return re.sub(r"[^A-Za-z0-9]+", "_", variant).strip("_")


def split_variant(args, variant):
    """([dem.coupling] lines, the sparing tolerance, [dem.numerics] lines, [mpm] lines): a part
    'sparing.tolerance = x' of the variant sets dem.sparing.tolerance for it (else --tolerance),
    a part 'numerics.KEY = x' sets dem.numerics.KEY (e.g. numerics.verlet_skin_min = 0.03), a part
    'mpm.KEY = x' sets mpm.KEY (e.g. mpm.wall_impulse = "points")."""
    lines, tol, numerics, mpm = [], args.tolerance, [], []
    for x in variant.split("+"):
        m = re.match(r"\s*sparing\.tolerance\s*=\s*(\S+)\s*$", x)
        n = re.match(r"\s*numerics\.(.*)$", x)
        g = re.match(r"\s*mpm\.(.*)$", x)
        if m:
            tol = float(m.group(1))
        elif n:
            numerics.append(n.group(1).strip())
        elif g:
            mpm.append(g.group(1).strip())
        else:
            lines.append(x.strip())
    return lines, tol, numerics, mpm


def run_name(scene, variant, tol, rep, perturbed):
    """The name of a run's job and output directory under --out (jobs/NAME.toml, runs/NAME)."""
    return "%s_%s_tol%g%s_rep%d" % (scene, slug(variant), tol, "" if not perturbed else
                                    "_perturbed" + ("_" + slug(perturbed) if isinstance(perturbed, str) else ""),
                                    rep)


def run(args, scene, variant, rep, perturbed):
    lines, tol, numerics, mpm = split_variant(args, variant)
    name = run_name(scene, variant, tol, rep, perturbed)
    job = os.path.join(args.out, "jobs", name + ".toml")
    out = os.path.join(args.out, "runs", name)
    os.makedirs(os.path.dirname(job), exist_ok=True)
    text = bs.job_text(scene, tol, args.max_spared, perturbed)
    assert "\n[dem.coupling]\n" in text, scene
    text = text.replace("\n[dem.coupling]\n", "\n[dem.coupling]\n" + "".join(x + "\n" for x in lines), 1)
    if mpm:
        assert "\n[mpm]\n" in text, scene
        text = text.replace("\n[mpm]\n", "\n[mpm]\n" + "".join(x + "\n" for x in mpm), 1)
    if numerics:
        assert "[dem.numerics]" not in text, scene
        text += "\n[dem.numerics]\n" + "".join(x + "\n" for x in numerics)
    with open(job, "w") as f:
        f.write(text)
    summary = os.path.join(out, "run_summary.json")
    if args.reuse and os.path.exists(summary):
        return (out,) + bs.read_summary(out)
    env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")
    cmd = ["nice", "-n", "5", "mpirun", "-n", str(args.np), args.exe, "run", job, "--out", out,
           "--force"]
    log = subprocess.run(cmd, env=env, cwd=bs.ROOT, capture_output=True, text=True)
    if log.returncode != 0:
        if getattr(args, "keep_going", False):  # tools/mpmxdem-tools coupling_bias --keep-going
            s = readers.summary(out, required=False)  # the error as the run reports it
            err = s["error"].split("\n")[0] if s and s.get("error") else log.stderr.strip()[-300:]
            print("run failed (exit %d): %s: %s" % (log.returncode, " ".join(cmd), err), flush=True)
            return None
        sys.exit("run failed (exit %d): %s\n%s" % (log.returncode, " ".join(cmd),
                                                   log.stderr[-3000:]))
    return (out,) + bs.read_summary(out)


def label(perturbed):
    """How a run's job differs from its variant's: '' or ', perturbed ...'."""
    if isinstance(perturbed, str):
        return ", perturbed: %s" % perturbed.replace("=>", " -> ")
    return ", perturbed 1e-6" if perturbed else ""


def ratio(base, runs, k):
    """Median over the repetitions of the reference's time over the variant's (NaN when a time
    is below the log's resolution)."""
    r = [b[k] / x[k] for b, x in zip(base, runs) if b[k] > 0 and x[k] > 0]
    return statistics.median(r) if r else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(bs.ROOT, "build", "mpmxdem"))
    ap.add_argument("--out", required=True)
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--scenes", default="footing")
    ap.add_argument("--refresh", default="", help="comma list of dt_refresh values; the first is the reference")
    ap.add_argument("--variants", default="",
                    help="';'-separated [dem.coupling] variants ('+' joins lines); the first is the reference")
    ap.add_argument("--tolerance", type=float, default=0.0, help="dem.sparing.tolerance of every run")
    ap.add_argument("--max-spared", type=int, default=20)
    ap.add_argument("--noise", action="store_true",
                    help="also the reference perturbed by 1e-6 (footing, biaxial and collapse scenes)")
    ap.add_argument("--perturb", action="append", default=[],
                    help="also the reference with the job text OLD replaced by NEW ('OLD=>NEW', "
                    "repeatable): more samples of the scene's sensitivity")
    ap.add_argument("--reuse", action="store_true",
                    help="analyse the runs already in --out (their run_summary.json) instead of running them")
    args = ap.parse_args()
    args.exe = os.path.abspath(args.exe)
    os.makedirs(args.out, exist_ok=True)
    if args.variants:
        variants_text = [v.strip() for v in args.variants.split(";")]
    else:
        variants_text = ["dt_refresh = %d" % int(x) for x in (args.refresh or "1,5,20,100").split(",")]
    rows = []
    for scene in args.scenes.split(","):
        kind = bs.SCENES[scene][2]
        variants = [(v, False) for v in variants_text] + (
            [(variants_text[0], True)] if args.noise else []) + [
            (variants_text[0], x) for x in args.perturb]
        res = {v: [] for v in variants}
        for rep in range(args.reps):
            for v in variants:  # alternating: every repetition runs every variant once
                out, wall, rve, work = run(args, scene, v[0], rep, v[1])
                res[v].append((out, wall, rve, work))
                print("%s [%s]%s rep %d: wall %.2f s, RVE %.2f s, %d DEM steps" % (
                    scene, v[0], label(v[1]), rep, wall, rve, work["dem_steps"]),
                    flush=True)
        base = res[variants[0]]
        ref = bs.measures(base[0][0], kind, base[0][3])
        for v in variants:
            m = bs.measures(res[v][0][0], kind, res[v][0][3])
            for other in res[v][1:]:  # every repetition gives the same bits: same DEM steps
                assert other[3]["dem_steps"] == m["dem_steps"], (scene, v)
            row = {"scene": scene, "variant": v[0] + label(v[1]), "perturbed": int(bool(v[1])),
                   "tolerance": split_variant(args, v[0])[1], "dem_steps": m["dem_steps"],
                   "dem_steps_ratio": m["dem_steps"] / ref["dem_steps"],
                   "wall_s": statistics.median(x[1] for x in res[v]),
                   "rve_s": statistics.median(x[2] for x in res[v]),
                   "wall_speedup": ratio(base, res[v], 1), "rve_speedup": ratio(base, res[v], 2)}
            row.update(bs.errors(kind, m, ref))
            rows.append(row)
    bs.write_csv(os.path.join(args.out, "bench_coupling.csv"), rows)
    lines = ["| scene | [dem.coupling] | DEM steps | against the reference | loop wall [s] | "
             "speed-up | RVE time [s] | speed-up | error against the reference (%s) |"
             % variants_text[0],
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %s | %d | %+.1f %% | %.1f | %.2fx | %.1f | %.2fx | %s |" % (
            r["scene"], r["variant"],
            r["dem_steps"], 100 * (r["dem_steps_ratio"] - 1), r["wall_s"],
            r["wall_speedup"], r["rve_s"], r["rve_speedup"], bs.error_text(r)))
    table = "\n".join(lines)
    print(table)
    with open(os.path.join(args.out, "bench_coupling.md"), "w") as f:
        f.write(table + "\n")


if __name__ == "__main__":
    main()
