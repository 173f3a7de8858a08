#!/usr/bin/python3
"""How the points of one grid cell share its vertical stress, in a column run.

docs/validation/column_collapse.md ("The points of a cell: one carries, three float"). The grid
sees a cell's points only through the nodal forces sum_p V_p sigma_p grad N_i(x_p): a pattern of
point stresses that repeats from cell to cell (one point loaded, its neighbours in the cell not)
gives the nodes nearly the forces of the cells' mean stresses wherever it repeats, so nothing
on the grid evens it out (the null space of the points-to-grid map: Gritton & Berzins 2017,
Computational Particle Mechanics 4, 131-142). A material without tension (an RVE that loses its
contacts) can then sit in such a pattern, its unloaded points free to dilate. Measured on a run,
at each output row, over the grid cells holding two
points or more whose vertical stress sum is positive ("loaded cells"; the vertical normal
stress -sigma_zz, positive in compression, carries the column's weight):

  share    the largest share of the cell's vertical stress sum carried by one of its points (n
           points: 1/n when they share it evenly, 1 when one point carries it all); median and
           90th percentile over the loaded cells;
  free     the fraction of the points of loaded cells that carry no vertical stress
           (-sigma_zz <= 0);
  quarter  over the cells holding four points, one in each quarter (lower-left, lower-right,
           upper-left, upper-right, x then z, in the cell): the mean share of each quarter;
  back     the same share and free fraction over the loaded cells of the upper back (cell
           centre at x < L0 / 4 from the back wall and z > 3 H0 / 4), where the stresses are a few Pa;
  J        the median of V / V0 over the points of the column's back quarter at the start
           (x0 < L0 / 4) and its upper quarter (z0 > 3 H0 / 4), and the median of their displacement
           [L0].

Modes:
  --analyse RUN STEM   reads RUN/results.h5, RUN/job.resolved.toml and RUN/job.toml; writes
                       DATA/STEM_cells.csv (one row per output row)
  --table STEM...      prints the page's table (rows nearest 0.5, 1, 2, 3 t* after the release)
  --self-test          checks the measure on synthetic cells (even, one point, a quarter pattern)

Times count from the gate's release (tools/mpmxdem_tools/analysis/column_grain_scale.py, gate_release), in t* =
sqrt(H0 / g). Usage: tools/mpmxdem-tools column_cell_stress [--data D] MODE. Default
D = docs/data/column_collapse_mpm_grain_scale. --analyse and --self-test need numpy (and h5py for
--analyse); --table the standard library only.
"""
import argparse
import csv
import math
import os
import sys

from . import column_grain_scale as cgs

from .. import readers
from ..paths import ROOT

TABLE_TIMES = (0.5, 1.0, 2.0, 3.0)
QUARTERS = ("ll", "lr", "ul", "ur")


def cell_shares(x, p, origin, spacing, region=None):
    """Per-row measure of the points' shares of a stress in their grid cells.

    x: [n, 3] positions [m], p: [n] stresses [Pa] (> 0 in compression), origin and spacing of
    the grid (x and z used); region: None, or a function of a cell's centre (x, z) [m] that keeps
    the cells for which it is true. Returns (median share, 90th percentile share, free fraction,
    {quarter: mean share}, loaded cells, four-point cells)."""
    import numpy as np
    u = (x[:, 0] - origin[0]) / spacing[0]
    w = (x[:, 2] - origin[2]) / spacing[2]
    ci, ck = np.floor(u).astype(np.int64), np.floor(w).astype(np.int64)
    quarter = (u - ci >= 0.5).astype(np.int64) + 2 * (w - ck >= 0.5).astype(np.int64)
    key = ci * 1_000_003 + ck
    order = np.argsort(key, kind="stable")
    key_s = key[order]
    starts = np.flatnonzero(np.r_[True, key_s[1:] != key_s[:-1]])
    ends = np.r_[starts[1:], len(key_s)]
    shares, free, points = [], 0, 0
    qsum, qcells = np.zeros(4), 0
    for a, b in zip(starts, ends):
        idx = order[a:b]
        if len(idx) < 2:
            continue
        if region is not None and not region(origin[0] + (ci[idx[0]] + 0.5) * spacing[0],
                                              origin[2] + (ck[idx[0]] + 0.5) * spacing[2]):
            continue
        pc = np.maximum(p[idx], 0.0)
        total = pc.sum()
        if not total > 0.0:
            continue
        shares.append(pc.max() / total)
        free += int((p[idx] <= 0.0).sum())
        points += len(idx)
        q = quarter[idx]
        if len(idx) == 4 and sorted(q.tolist()) == [0, 1, 2, 3]:
            for j in range(4):
                qsum[q[j]] += pc[j] / total
            qcells += 1
    if not shares:
        return math.nan, math.nan, math.nan, {k: math.nan for k in QUARTERS}, 0, 0
    qmean = {k: (qsum[j] / qcells if qcells else math.nan) for j, k in enumerate(QUARTERS)}
    return (float(np.median(shares)), float(np.percentile(shares, 90)), free / points, qmean,
            len(shares), qcells)


def analyse(run, stem, data):
    import numpy as np
    job, L0, H0, tstar, release = cgs.column_of_run(run)
    grid = job["mpm"]["grid"]
    origin, spacing = grid["origin"], grid["spacing"]
    body = job["mpm"]["body"][0]
    with readers.results(run) as f:
        t = f["time"][:]
        x = f["points/x"][:]
        p = -f["points/stress"][:, :, 8]  # -sigma_zz [Pa]
        V = f["points/volume"][:]
        d = f["points/displacement"][:]
    back = (x[0, :, 0] - body["min"][0] < L0 / 4) & (x[0, :, 2] - body["min"][2] > 0.75 * H0)
    x_back, z0 = body["min"][0] + L0 / 4, body["min"][2]

    def upper_back(cx, cz):
        return cx < x_back and cz - z0 > 0.75 * H0

    rows = []
    for k in range(len(t)):
        med, p90, free, q, cells, qcells = cell_shares(x[k], p[k], origin, spacing)
        b_med, _, b_free, _, b_cells, _ = cell_shares(x[k], p[k], origin, spacing, upper_back)
        rows.append({
            "t_over_tstar": (t[k] - release) / tstar,
            "share_median": med, "share_p90": p90, "free_fraction": free,
            **{f"quarter_{n}": q[n] for n in QUARTERS},
            "loaded_cells": cells, "four_point_cells": qcells,
            "back_share_median": b_med, "back_free_fraction": b_free, "back_loaded_cells": b_cells,
            "back_J_median": float(np.median(V[k, back] / V[0, back])),
            "back_displacement_median_L0": float(np.median(np.linalg.norm(d[k, back], axis=1)) / L0),
        })
    os.makedirs(data, exist_ok=True)
    out = os.path.join(data, f"{stem}_cells.csv")
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.5g}" if isinstance(v, float) else v) for k, v in r.items()})
    print(f"column_cell_stress: {stem}: {len(rows)} rows, {int(back.sum())} points in the upper back; "
          f"written {out}")


def table(stems, data):
    print("| run | t / t* | largest share of a cell's vertical stress on one point: median / 90 % | "
          "points of loaded cells without vertical stress | mean share of each quarter: lower-left / "
          "lower-right / upper-left / upper-right | upper back: largest share (median), points "
          "without vertical stress | upper back: V / V0, displacement / L0 (medians) |")
    print("|---|---|---|---|---|---|---|")
    for stem in stems:
        with open(os.path.join(data, f"{stem}_cells.csv")) as f:
            rows = list(csv.DictReader(f))
        for want in TABLE_TIMES:
            r = min(rows, key=lambda r: abs(float(r["t_over_tstar"]) - want))
            if abs(float(r["t_over_tstar"]) - want) > 0.25:
                continue
            q = " / ".join(f"{float(r['quarter_' + n]):.2f}" for n in QUARTERS)
            back = (f"{float(r['back_share_median']):.2f}, {100 * float(r['back_free_fraction']):.0f} %"
                    if int(r["back_loaded_cells"]) else "no loaded cell left")
            print(f"| {stem} | {float(r['t_over_tstar']):.2f} | {float(r['share_median']):.2f} / "
                  f"{float(r['share_p90']):.2f} | {100 * float(r['free_fraction']):.0f} % | {q} | "
                  f"{back} | "
                  f"{float(r['back_J_median']):.3f}, {float(r['back_displacement_median_L0']):.4f} |")


def self_test():
    import numpy as np
    origin, spacing = [0.0, 0.0, 0.0], [1.0, 1.0, 1.0]
    # Two cells of four points at the quarter points.
    sub = [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)]
    x = np.array([[c + a, 0.5, b] for c in (0.0, 1.0) for a, b in sub])
    even = np.full(8, 10.0)
    med, p90, free, q, cells, qcells = cell_shares(x, even, origin, spacing)
    assert abs(med - 0.25) < 1e-12 and abs(p90 - 0.25) < 1e-12 and free == 0.0, (med, p90, free)
    assert cells == 2 and qcells == 2 and all(abs(q[n] - 0.25) < 1e-12 for n in QUARTERS), q
    # One point (lower-right) carries each cell; the others are stress-free or in tension.
    one = np.array([0.0, 33.0, -1e-9, 0.0, 0.0, 40.0, 0.0, 0.0])
    med, p90, free, q, cells, qcells = cell_shares(x, one, origin, spacing)
    assert abs(med - 1.0) < 1e-12 and abs(free - 6 / 8) < 1e-12, (med, free)
    assert abs(q["lr"] - 1.0) < 1e-12 and q["ll"] == 0.0 and q["ur"] == 0.0, q
    # A cell without stress is not a loaded cell; a lone point is not counted.
    x2 = np.vstack([x, [[5.5, 0.5, 5.5]]])
    p2 = np.r_[np.zeros(4), even[4:], 7.0]
    med, p90, free, q, cells, qcells = cell_shares(x2, p2, origin, spacing)
    assert cells == 1 and qcells == 1 and abs(med - 0.25) < 1e-12, (cells, med)
    # Three points in a cell (one moved out): shares of three, no quarter pattern.
    p3 = np.array([30.0, 10.0, 0.0, 0.0, 5.0, 5.0, 5.0, 5.0])
    x3 = x.copy()
    x3[3] = [2.6, 0.5, 0.6]
    med, p90, free, q, cells, qcells = cell_shares(x3, p3, origin, spacing)
    # cell 0: 30 / 10 / 0 (share 0.75, one free point); cell 1 even (0.25); the moved point alone.
    assert cells == 2 and qcells == 1 and abs(med - 0.5) < 1e-12 and abs(p90 - 0.7) < 1e-12, (med, p90)
    assert abs(free - 1 / 7) < 1e-12 and abs(q["ll"] - 0.25) < 1e-12, (free, q)
    # A region keeps only the cells whose centre it accepts (here: the second cell, x > 1).
    med, p90, free, q, cells, qcells = cell_shares(x, one, origin, spacing, lambda cx, cz: cx > 1.0)
    assert cells == 1 and abs(med - 1.0) < 1e-12 and abs(free - 0.75) < 1e-12, (cells, med, free)
    print("column_cell_stress: self-test ok (even, one point, unloaded cell, lone point, three points, a region)")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", default=os.path.join(ROOT, "docs", "data", "column_collapse_mpm_grain_scale"))
    ap.add_argument("--analyse", nargs=2, metavar=("RUN", "STEM"))
    ap.add_argument("--table", nargs="+", metavar="STEM")
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.analyse:
        analyse(a.analyse[0], a.analyse[1], a.data)
    elif a.table:
        table(a.table, a.data)
    elif a.self_test:
        self_test()
    else:
        ap.print_help()
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
