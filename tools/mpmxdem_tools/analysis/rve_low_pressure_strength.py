#!/usr/bin/python3
"""The RVEs' strength at a scene's own pressure: plane-strain biaxial tests of a scene's grains,
100 and 1000 spheres, from the jobs stored in a data folder. The column's (contact modulus 3 MPa,
at 30 Pa; docs/validation/column_collapse.md, "What friction the column needs") are the default;
the footing's (300 MPa, at 50 kPa; docs/validation/footing.md) are
--data docs/data/footing_rve_strength. Modes:

  --run DIR     runs every job docs/data/column_collapse_rve_strength/*.toml with
                `build/mpmxdem dem JOB --out DIR/<stem>` (one thread each; about a minute in all;
                DIR/<stem>.log is each run's log)
                and copies each run's dem_series.csv to DATA/<stem>_series.csv
  --table       prints the page's table from DATA/*_series.csv (standard library only)
  --dilatancy   adds the dilatancy angle at the peak to the table
  --early-dilatancy
                adds the dilatancy angle over the first 2 % of axial strain (a dense sample's
                first failure, where a 100-sphere RVE's peak row can come late and noisy)
  --dilation    adds the dilation at the end of the test, ln(V / V0) = -eps_v (the volumetric
                strain from the dense state to the critical state: what a continuum's dilatancy
                cut-off, mpm.elastic.dilatancy_cutoff, stands for)

Usage: tools/mpmxdem-tools rve_low_pressure_strength [--data D] [--exe E] (--run DIR | --table)
       [--dilatancy] [--early-dilatancy] [--dilation]
Defaults: D = docs/data/column_collapse_rve_strength, E = build/mpmxdem.

The mobilised friction angle of a plane-strain test is asin((s1 - s3) / (s1 + s3)), s1 the axial
and s3 the lateral (x) stress, compression positive. Peak: the largest mean over 5 consecutive
rows (about 0.6 % of axial strain: a 100-sphere RVE's single rows are noisy); critical state: the
mean over axial strains above 15 %, with its standard deviation over the rows. Dilatancy angle at
the peak (--dilatancy): asin(-d eps_v / (d eps_a - d eps_x)) over the peak's rows (plane strain:
eps_x = eps_v - eps_a; compression positive); over the first 2 % (--early-dilatancy): the same
from the first row to the first row at 2 % of axial strain or more.
"""
import argparse
import csv
import glob
import math
import os
import shutil
import subprocess

from ..paths import ROOT
WINDOW = 5  # rows of the peak's running mean


def mobilised(series_path):
    """(peak angle [deg], critical angle [deg], its standard deviation [deg], void ratio at the end,
    coordination at the end) of one dem_series.csv."""
    rows = list(csv.DictReader(open(series_path)))
    eps = [float(r["eps_a"]) for r in rows]
    s = []
    for r in rows:
        s1, s3 = -float(r["szz"]), -float(r["sxx"])
        s.append((s1 - s3) / (s1 + s3))
    runs = [sum(s[i:i + WINDOW]) / WINDOW for i in range(len(s) - WINDOW + 1)]
    late = [x for x, e in zip(s, eps) if e > 0.15]
    mean = sum(late) / len(late)
    sd = (sum((x - mean) ** 2 for x in late) / len(late)) ** 0.5
    crit = math.degrees(math.asin(mean))
    sd_deg = math.degrees(math.asin(min(mean + sd, 1.0))) - crit
    return (math.degrees(math.asin(max(runs))), crit, sd_deg, float(rows[-1]["e"]),
            float(rows[-1]["Z"]))


def dilatancy_between(rows, i, j):
    """Dilatancy angle [deg] of a plane-strain test between rows i and j: asin(-d eps_v /
    (d eps_a - d eps_x)), eps_x = eps_v - eps_a, compression positive."""
    da = float(rows[j]["eps_a"]) - float(rows[i]["eps_a"])
    dv = float(rows[j]["eps_v"]) - float(rows[i]["eps_v"])
    return math.degrees(math.asin(-dv / (2 * da - dv)))


def dilatancy_at_peak(series_path):
    """Dilatancy angle [deg] over the rows of the peak's running mean (see mobilised)."""
    rows = list(csv.DictReader(open(series_path)))
    s = [(-float(r["szz"]) + float(r["sxx"])) / (-float(r["szz"]) - float(r["sxx"])) for r in rows]
    runs = [sum(s[i:i + WINDOW]) / WINDOW for i in range(len(s) - WINDOW + 1)]
    i = max(range(len(runs)), key=runs.__getitem__)
    j = min(i + WINDOW - 1, len(rows) - 1)
    return dilatancy_between(rows, max(i - 1, 0), j)


def early_dilatancy(series_path, strain=0.02):
    """Dilatancy angle [deg] from the first row to the first at `strain` of axial strain."""
    rows = list(csv.DictReader(open(series_path)))
    return dilatancy_between(rows, 0, next(k for k, r in enumerate(rows) if float(r["eps_a"]) >= strain))


def stems(data):
    return sorted((os.path.basename(p)[:-len(".toml")] for p in glob.glob(os.path.join(data, "*.toml"))),
                  key=lambda n: (int(n.split("_")[0][1:]), n))


def dilation_at_end(series_path):
    """ln(V / V0) at the last row: -eps_v (eps_v = -ln(V / V0), compression positive)."""
    rows = list(csv.DictReader(open(series_path)))
    return -float(rows[-1]["eps_v"])


def table(data, dilatancy=False, early=False, dilation=False):
    lines = ["| RVE | spheres | peak friction angle | " + ("dilatancy angle at the peak | " if dilatancy else "")
             + ("dilatancy angle over the first 2 % | " if early else "")
             + "critical-state friction angle (axial strain > 15 %) "
             "| void ratio at 30 % | " + ("dilation ln(V / V0) at 30 % | " if dilation else "")
             + "coordination at 30 % |",
             "|---|---|---|---|---|---|" + ("---|" if dilatancy else "") + ("---|" if early else "")
             + ("---|" if dilation else "")]
    for stem in stems(data):
        path = os.path.join(data, f"{stem}_series.csv")
        if not os.path.exists(path):
            continue
        peak, crit, sd, e, z = mobilised(path)
        n, seed = stem.split("_")
        psi = f"{dilatancy_at_peak(path):.1f} deg | " if dilatancy else ""
        psi += f"{early_dilatancy(path):.1f} deg | " if early else ""
        dv = f"{dilation_at_end(path):.3f} | " if dilation else ""
        lines.append(f"| seed {seed[len('seed'):]} | {n[1:]} | {peak:.1f} deg | {psi}{crit:.1f} +- {sd:.1f} deg | "
                     f"{e:.3f} | {dv}{z:.2f} |")
    return "\n".join(lines)


def run(data, exe, out):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    for stem in stems(data):
        work = os.path.join(out, stem)
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(out, exist_ok=True)
        with open(os.path.join(out, f"{stem}.log"), "w") as log:  # the run's log beside its folder
            subprocess.run([exe, "dem", os.path.join(data, f"{stem}.toml"), "--out", work], env=env,
                           check=True, stdout=log, stderr=subprocess.STDOUT)
        shutil.copy(os.path.join(work, "dem_series.csv"), os.path.join(data, f"{stem}_series.csv"))
        print("ran", stem, flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", default=os.path.join(ROOT, "docs", "data", "column_collapse_rve_strength"))
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "mpmxdem"))
    ap.add_argument("--run", metavar="DIR")
    ap.add_argument("--table", action="store_true")
    ap.add_argument("--dilatancy", action="store_true", help="the table with the dilatancy angle at the peak")
    ap.add_argument("--early-dilatancy", action="store_true",
                    help="the table with the dilatancy angle over the first 2 %% of axial strain")
    ap.add_argument("--dilation", action="store_true",
                    help="the table with the dilation ln(V / V0) at the end (dense to critical state)")
    args = ap.parse_args()
    if args.run:
        run(args.data, args.exe, args.run)
    if args.table:
        print(table(args.data, args.dilatancy, args.early_dilatancy, args.dilation))
    if not (args.run or args.table):
        ap.error("one of --run DIR, --table")


if __name__ == "__main__":
    main()
