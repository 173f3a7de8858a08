#!/usr/bin/python3
"""The column's macro inertial number and its RVEs' inertial number, at the same points.

docs/validation/column_collapse.md ("Rate: where the RVEs run at the material's rate"). An MPM x
DEM point shears its RVE at I_RVE = max(I_n, I_m) (dem.coupling.rate = "material",
docs/design/rve_step.md): the coupling inertial number I_n where the material is slower than it,
the material's own I_m where it is faster. Measured on a run, with the code's own definitions:

  I_m   = (e / dt) t_i over the output interval before the row: e the largest strain component
          |sym(dF F^-1)_ab| of the point between two output rows, dt their time apart, t_i =
          d50 sqrt(rho_s / p) with p the point's RVE pressure floored at dem.coupling.pressure_floor
          (as the RVE step does), d50 the mass median of dem.sample's grading, rho_s the grains'
          density;
  I_RVE = I_m where the RVE ran the row's step at the material's rate (rve/guards bit 5,
          kGuardMaterialRate), I_n where it ran quasi-statically; none where it was held without
          contacts (bit 6, kGuardDisconnected: no DEM step, no rate).

Modes:
  --analyse RUN STEM   reads RUN/results.h5 and RUN/job.resolved.toml; writes DATA/STEM_inertial.csv
                       (per output row: I_m median / 95th percentile / maximum over the points that
                       move, how many RVEs ran at the material's rate, quasi-statically, held) and
                       DATA/STEM_inertial_points.csv (every point at the rows nearest 0.5, 1 and 2 t*
                       after the gate's release: position, I_m, I_RVE, guards)
  --table STEM...      prints the page's table (rows nearest 0.5, 1, 2, 3 t* after the release)
  --figure STEM        writes FIG/column_inertial_numbers.png: the points of STEM at 1 and 2 t*
                       after the release coloured by I_m (left) and by I_RVE (right), one scale
  --self-test          checks the rate measure on a synthetic simple shear

Times count from the gate's release (tools/mpmxdem_tools/analysis/column_grain_scale.py, gate_release), in t* =
sqrt(H0 / g). Usage: tools/mpmxdem-tools column_inertial_numbers [--data D] [--fig F] MODE.
Defaults: D = docs/data/column_collapse_mpm_grain_scale, F = docs/figures. --analyse and --self-test
need numpy and h5py (--analyse), --figure matplotlib; --table the standard library only.
"""
import argparse
import csv
import math
import os
import sys

from . import column_grain_scale as cgs

from .. import readers
from ..paths import ROOT

GUARD_MATERIAL_RATE = 1 << 5  # dem::kGuardMaterialRate
GUARD_DISCONNECTED = 1 << 6  # dem::kGuardDisconnected
TIMES = (0.5, 1.0, 2.0)  # t / t* after the release of the per-point rows
TABLE_TIMES = (0.5, 1.0, 2.0, 3.0)
FIGURE_TIMES = (1.0, 2.0)
MOVING = 1e-3  # a point "moves" in a row when I_m exceeds this (the static core's I_m is ~0)


def d50_of_grading(diameters, passing):
    """Mass-median diameter of a grading given as (diameter, mass fraction passing) points, linear
    between them."""
    for k in range(1, len(diameters)):
        if passing[k] >= 0.5:
            f = (0.5 - passing[k - 1]) / (passing[k] - passing[k - 1])
            return diameters[k - 1] + f * (diameters[k] - diameters[k - 1])
    return diameters[-1]


def strain_rate_max(F0, F1, dt):
    """Largest |sym(dF F^-1)_ab| / dt of each point between F0 and F1 ([m, 3, 3] each)."""
    import numpy as np
    G = (F1 - F0) @ np.linalg.inv(F0)
    D = 0.5 * (G + np.transpose(G, (0, 2, 1)))
    return np.abs(D).reshape(len(D), 9).max(axis=1) / dt


def analyse(run, stem, data):
    import numpy as np
    job, L0, H0, tstar, release = cgs.column_of_run(run)
    dem = job["dem"]
    i_n = float(dem["coupling"]["inertial_number"])
    floor = float(dem["coupling"]["pressure_floor"])
    rho = float(dem["material"]["density"])
    d50 = d50_of_grading(dem["sample"]["psd_diameters"], dem["sample"]["psd_passing"])
    with readers.results(run) as f:
        t = f["time"][:]
        x = f["points/x"][:]
        F = f["points/F"][:].reshape(len(t), -1, 3, 3)
        p = f["points/p"][:]
        guards = f["rve/guards"][:]
        if not np.array_equal(f["rve/id"][:], f["points/id"][:]):
            sys.exit("column_inertial_numbers: rve/id and points/id differ (one RVE per point expected)")
    rows, im_rows = [], []
    for k in range(1, len(t)):
        pk = np.maximum(p[k], floor)
        im = strain_rate_max(F[k - 1], F[k], t[k] - t[k - 1]) * d50 * np.sqrt(rho / pk)
        g = guards[k].astype(np.int64)
        held = (g & GUARD_DISCONNECTED) != 0
        material = ((g & GUARD_MATERIAL_RATE) != 0) & ~held
        irve = np.where(material, im, i_n)
        irve[held] = np.nan
        moving = im[im > MOVING]
        rows.append({
            "t_over_tstar": (t[k] - release) / tstar,
            "im_median": float(np.median(moving)) if len(moving) else 0.0,
            "im_p95": float(np.percentile(moving, 95)) if len(moving) else 0.0,
            "im_max": float(im.max()),
            "points_moving": int(len(moving)),
            "rves_material_rate": int(material.sum()),
            "rves_quasi_static": int((~material & ~held).sum()),
            "rves_held": int(held.sum()),
            "points": int(len(im)),
        })
        im_rows.append((k, im, irve, g))
    os.makedirs(data, exist_ok=True)
    with open(os.path.join(data, f"{stem}_inertial.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    with open(os.path.join(data, f"{stem}_inertial_points.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t_over_tstar", "x_over_L0", "z_over_L0", "i_m", "i_rve", "guards", "i_n"])
        for want in TIMES:
            j = min(range(len(rows)), key=lambda q: abs(rows[q]["t_over_tstar"] - want))
            k, im, irve, g = im_rows[j]
            for q in range(len(im)):
                w.writerow([f"{rows[j]['t_over_tstar']:.4f}", f"{x[k, q, 0] / L0:.5f}",
                            f"{x[k, q, 2] / L0:.5f}", f"{im[q]:.4g}",
                            "" if math.isnan(irve[q]) else f"{irve[q]:.4g}", int(g[q]), f"{i_n:g}"])
    print(f"column_inertial_numbers: {stem}: {len(rows)} rows, d50 = {d50 * 1e6:.0f} um, I_n = {i_n:g}, "
          f"p floor {floor:g} Pa; written {data}/{stem}_inertial*.csv")


def read(data, stem, kind="inertial"):
    with open(os.path.join(data, f"{stem}_{kind}.csv")) as f:
        return list(csv.DictReader(f))


def table(stems, data):
    print("| run | t / t* | points that move (I_m > 1e-3) | I_m of those: median / 95 % / max | "
          "RVEs at the material's rate / quasi-static / held without contacts |")
    print("|---|---|---|---|---|")
    for stem in stems:
        rows = read(data, stem)
        for want in TABLE_TIMES:
            r = min(rows, key=lambda r: abs(float(r["t_over_tstar"]) - want))
            if abs(float(r["t_over_tstar"]) - want) > 0.25:
                continue
            print(f"| {stem} | {float(r['t_over_tstar']):.2f} | {r['points_moving']} of {r['points']} | "
                  f"{float(r['im_median']):.3f} / {float(r['im_p95']):.3f} / {float(r['im_max']):.3f} | "
                  f"{r['rves_material_rate']} / {r['rves_quasi_static']} / {r['rves_held']} |")


def figure(stem, data, fig_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm
    fig, axs = plt.subplots(2, 2, figsize=(10, 9.5), squeeze=False)
    norm = LogNorm(1e-3, 1.0)
    rows = read(data, stem, "inertial_points")
    for row, want in enumerate(FIGURE_TIMES):
        pts = [r for r in rows if abs(float(r["t_over_tstar"]) - want) < 0.25]
        t = float(pts[0]["t_over_tstar"])
        xs = [float(r["x_over_L0"]) for r in pts]
        zs = [float(r["z_over_L0"]) for r in pts]
        im = [max(float(r["i_m"]), 1e-3) for r in pts]
        held = [r["i_rve"] == "" for r in pts]
        irve = [max(float(r["i_rve"]), 1e-3) if r["i_rve"] else 1e-3 for r in pts]
        i_n = float(pts[0]["i_n"])
        for col, (vals, what) in enumerate(((im, "I_m, the material's"), (irve, "I_RVE, its RVE's"))):
            ax = axs[row, col]
            sc = ax.scatter(xs, zs, c=vals, s=3, norm=norm, cmap="viridis", linewidths=0)
            if col == 1:
                hx = [xv for xv, h in zip(xs, held) if h]
                hz = [zv for zv, h in zip(zs, held) if h]
                ax.scatter(hx, hz, s=3, color="red", linewidths=0,
                           label=f"held without contacts ({len(hx)} of {len(xs)})")
                ax.legend(fontsize=7, loc="upper right")
            ax.set_aspect("equal")
            ax.set_title(f"{what} inertial number, {t:.2f} t* after the release (I_n = {i_n:g})",
                         fontsize=8)
            ax.set_xlabel("x / L0")
            ax.set_ylabel("z / L0")
            fig.colorbar(sc, ax=ax, shrink=0.7, label="inertial number")
    fig.suptitle(f"{stem}: each point at its place, coloured by I_m (left) and I_RVE (right)",
                 fontsize=9)
    fig.tight_layout()
    out = os.path.join(fig_dir, "column_inertial_numbers.png")
    fig.savefig(out, dpi=120)
    print(f"column_inertial_numbers: wrote {out}")


def self_test():
    import numpy as np
    # Simple shear at rate g: F = [[1, g t, 0], [0, 1, 0], [0, 0, 1]]: sym(dF F^-1)_xz = g dt / 2.
    g, t0, dt = 3.0, 0.2, 0.01
    F0 = np.array([[[1.0, g * t0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]])
    F1 = np.array([[[1.0, g * (t0 + dt), 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]])
    e = strain_rate_max(F0, F1, dt)[0]
    assert abs(e - g / 2) < 1e-12, e
    # A uniaxial stretch at rate r: ln stretch rate r, dF F^-1 = r dt / (1 + r t0) to first order.
    r = 0.5
    F0 = np.diag([1.0 + r * t0, 1.0, 1.0])[None]
    F1 = np.diag([1.0 + r * (t0 + dt), 1.0, 1.0])[None]
    assert abs(strain_rate_max(F0, F1, dt)[0] - r / (1 + r * t0)) < 1e-12
    assert abs(d50_of_grading([130e-6, 270e-6], [0.0, 1.0]) - 200e-6) < 1e-15
    assert abs(d50_of_grading([1.0, 2.0, 4.0], [0.0, 0.25, 1.0]) - (2.0 + 2.0 / 3.0)) < 1e-12
    print("column_inertial_numbers: self-test ok (shear and stretch rates, d50 of a grading)")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", default=os.path.join(ROOT, "docs", "data", "column_collapse_mpm_grain_scale"))
    ap.add_argument("--fig", default=os.path.join(ROOT, "docs", "figures"))
    ap.add_argument("--analyse", nargs=2, metavar=("RUN", "STEM"))
    ap.add_argument("--table", nargs="+", metavar="STEM")
    ap.add_argument("--figure", metavar="STEM")
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.analyse:
        analyse(a.analyse[0], a.analyse[1], a.data)
    elif a.table:
        table(a.table, a.data)
    elif a.figure:
        figure(a.figure, a.data, a.fig)
    elif a.self_test:
        self_test()
    else:
        ap.print_help()
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
