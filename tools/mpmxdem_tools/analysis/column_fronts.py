#!/usr/bin/python3
"""The column's front measured alike on an MPM x DEM run and on a pure-DEM column: where the deposit first falls below 0.05 H0.

docs/validation/column_collapse.md ("Damping"). The "continuous front" of the other tables is not
measured alike in the two kinds of column: the MPM x DEM one ends at the first gap wider than 1.5
point spacings (a film of single points counts), the grains' at the first d50 bin lower than d50.
This tool measures both as the runout of the tables is measured: walking from the back wall, the
first x where the deposit's height at the initial density, h_vol, falls below 0.05 H0
(column_grain_scale.deposit_end, linear between bin centres), at 1, 2 and 3 t* after the release
(an MPM x DEM run: linear between the two output rows around the time) and at the end;
(x - L0) / L0.

Modes:
  --analyse RUN STEM  reads RUN/results.h5 (points/x, points/volume) and RUN/job.toml (the gate's
                      release); bins the points' initial volumes on bins of one point spacing (as
                      mpm_column_collapse's profiles); writes DATA/STEM_fronts05.csv
  --table ITEM...     prints one row per ITEM: an MPM x DEM stem with DATA/STEM_fronts05.csv, or a
                      YADE tag with YADE/TAG_profiles.csv (its rows at 1, 2, 3 t* and "final")
  --self-test         checks the measure on a synthetic deposit

Usage: tools/mpmxdem-tools column_fronts [--data D] [--yade Y] MODE. Defaults: D =
docs/data/column_collapse_mpm_grain_scale, Y = docs/data/column_collapse_yade. --analyse needs numpy
and h5py; --table and --self-test the standard library only.
"""
import argparse
import math
import os
import sys

from . import column_grain_scale as cgs
from ..paths import ROOT

G = 9.81
LEVEL = 0.05  # of H0
TIMES = ("1", "2", "3", "final")


def front(xs, hs, L0, H0):
    """(x - L0) / L0 where the deposit (bin centres xs, heights hs) first falls below LEVEL H0."""
    return (cgs.deposit_end(xs, hs, LEVEL * H0) - L0) / L0


def analyse(run, stem, data):
    import h5py
    import numpy as np
    with h5py.File(os.path.join(run, "results.h5"), "r") as f:
        t = f["time"][:]
        x = f["points/x"]
        vol0 = f["points/volume"][0]
        x0 = x[0]
        xs0, zs0 = np.unique(np.round(x0[:, 0], 9)), np.unique(np.round(x0[:, 2], 9))
        dx, dz = xs0[1] - xs0[0], zs0[1] - zs0[0]
        L0, H0 = x0[:, 0].max() + dx / 2, x0[:, 2].max() + dz / 2
        thick = vol0[0] / (dx * dz)
        tstar = math.sqrt(H0 / G)
        release = cgs.gate_release(os.path.join(run, "job.toml"))
        def front_at(k):
            xk = x[k][:, 0]
            edges = np.arange(int(np.ceil((xk.max() + dx) / dx)) + 2) * dx
            hv = np.histogram(xk, bins=edges, weights=vol0)[0] / (dx * thick)
            return front(list(0.5 * (edges[1:] + edges[:-1])), list(hv), L0, H0)

        rows = [("final", (t[-1] - release) / tstar, front_at(len(t) - 1))]
        for label in TIMES[:-1]:  # linear between the two output rows around the time
            target = release + int(label) * tstar
            k = min(max(int(np.searchsorted(t, target)), 1), len(t) - 1)
            w = (target - t[k - 1]) / (t[k] - t[k - 1])
            rows.insert(len(rows) - 1, (label, int(label), (1 - w) * front_at(k - 1) + w * front_at(k)))
    os.makedirs(data, exist_ok=True)
    path = os.path.join(data, f"{stem}_fronts05.csv")
    with open(path, "w") as o:
        o.write("t_label,t_over_tstar,front05_over_L0\n")
        for label, tt, fr in rows:
            o.write(f"{label},{tt:.4f},{fr:.4f}\n")
    print(f"wrote {path}")


def profile_fronts(folder, tag):
    """The fronts at TIMES of a column with FOLDER/TAG_summary.csv (L0_m, H0_m) and TAG_profiles.csv:
    a YADE column's, or an MPM x DEM run's (its profiles hold only the "final" rows: nan at 1-3 t*)."""
    summary = cgs.read_csv(os.path.join(folder, f"{tag}_summary.csv"))[0]
    L0, H0 = float(summary["L0_m"]), float(summary["H0_m"])
    profiles = cgs.read_csv(os.path.join(folder, f"{tag}_profiles.csv"))
    out = []
    for label in TIMES:
        rows = sorted((float(r["x_m"]), float(r["h_vol_m"])) for r in profiles if r["t_over_tstar"] == label)
        out.append(front([r[0] for r in rows], [r[1] for r in rows], L0, H0) if rows else float("nan"))
    return out


def table(items, data, yade):
    lines = ["| column | front to 0.05 H0 at 1 t* | at 2 t* | at 3 t* | at the end (the runout) |",
             "|---|---|---|---|---|"]
    for item in items:
        path = os.path.join(data, f"{item}_fronts05.csv")
        if os.path.exists(path):
            by = {r["t_label"]: float(r["front05_over_L0"]) for r in cgs.read_csv(path)}
            values = [by.get(label, float("nan")) for label in TIMES]
            name = f"MPM x DEM {item}"
        else:
            values = profile_fronts(yade, item)
            name = f"pure DEM (YADE) {item}"
        lines.append(f"| {name} | " + " | ".join(f"{v:.2f}" for v in values) + " |")
    return "\n".join(lines)


def self_test():
    """A deposit of height H0 to x = L0, then falling linearly to 0 at 2 L0: the 0.05 H0 front is
    at 1.95 L0 ((x - L0) / L0 = 0.95); a detached heap beyond a gap does not count."""
    L0, H0, n = 1.0, 0.5, 200
    xs = [(i + 0.5) * 2.0 * L0 / n for i in range(n)] + [2.5, 2.6]
    hs = [H0 if x <= L0 else H0 * (2.0 * L0 - x) / L0 for x in xs[:n]] + [H0, H0]
    got = front(xs, hs, L0, H0)
    assert abs(got - 0.95) < 1e-9, got
    print("column_fronts self-test: ok")


def main():
    ap = argparse.ArgumentParser(prog="mpmxdem-tools column_fronts", description=__doc__.split("\n")[0])
    ap.add_argument("--data", default=os.path.join(ROOT, "docs", "data", "column_collapse_mpm_grain_scale"))
    ap.add_argument("--yade", default=os.path.join(ROOT, "docs", "data", "column_collapse_yade"))
    ap.add_argument("--analyse", nargs=2, metavar=("RUN_DIR", "STEM"))
    ap.add_argument("--table", nargs="+", metavar="ITEM")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    if args.self_test:
        self_test()
    elif args.analyse:
        analyse(*args.analyse, args.data)
    elif args.table:
        print(table(args.table, args.data, args.yade))
    else:
        ap.print_usage()
        sys.exit(2)


if __name__ == "__main__":
    main()
