#!/usr/bin/python3
"""Figures of a drained triaxial test, like Duverger et al. 2022 (figs. 1 and 2).

Usage (Debian's python3-matplotlib and python3-h5py; use /usr/bin/python3):
  tools/mpmxdem-tools plot_triaxial --out FIG_PREFIX [--run DIR[=LABEL]]... [--csv FILE[=LABEL]]... [--summary]

  --run DIR   an `mpmxdem run` output directory (means.csv, results.h5): sample means, and
              per-RVE principal stresses, coordination number and axial over lateral stress
              (an `mpmxdem dem` directory is plotted as its dem_series.csv)
  --csv FILE  a series with columns eps_a, eps_v, q (and p): `mpmxdem dem` (dem_series.csv),
              triax_dem, or YADE's yade_triax_*.csv
q is sigma_a - sigma_r in every figure (the paper's q; from sig_a and sig_r where a series has
them, from the mean RVE stress of a run); --summary prints the mean von Mises q of the RVEs
(means.csv), the figure docs/validation/triaxial.md quotes. A series whose lateral stress strays more than
5 % from its start (after 0.1 % axial strain) is plotted with a warning: its control failed.
One colour per RVE in every panel of the RVE figure.
Writes FIG_PREFIX_q_epsv.png (fig. 1: q and eps_v against eps_ax, every source) and, for each
--run, FIG_PREFIX_rves_<n>.png (fig. 2). Compression positive throughout. Strains are logarithmic, -ln(stretch), as in the DEM series;
the MPM means (1 - F_zz, 1 - V/V0) are converted. The MPM cell is fixed, so the platen of eq. 13
imposes L_zz = -V/h: after a time t the log strain is V t / h (195 s of the paper's job: 0.30).
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from .. import readers


def split_label(arg):
    path, _, label = arg.partition("=")
    return path, label or os.path.basename(os.path.normpath(path))


def read_csv(path):
    # means.csv and dem_series.csv start with their header line (pandas.read_csv reads them as
    # they are); '#' lines are skipped for the means.csv of older runs and YADE's files.
    with open(path) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    head = rows[0]
    data = np.array([[float(v) for v in r] for r in rows[1:] if r], dtype=float)
    return {name: data[:, i] for i, name in enumerate(head)}


LATERAL_TOLERANCE = 0.05  # as `mpmxdem dem`'s dem.loading.lateral_tolerance default


def series_of_csv(path, label=None, q_column=False):
    """eps_a, eps_v and q = sigma_a - sigma_r (the paper's q; YADE's `q` column is that, while
    the `q` of dem_series.csv is the von Mises q, shear included: both files carry sig_a, sig_r).
    q_column: the file's own `q` column instead (tools/mpmxdem_tools/bench/bench_speed_error.py, whose figures in
    docs/validation/speed.md were computed so)."""
    label = label or path
    d = read_csv(path)
    q = d["sig_a"] - d["sig_r"] if "sig_a" in d and "sig_r" in d and not q_column else d["q"]
    if "sxx" in d and "syy" in d:
        # A test whose servo lost the lateral stress is another test: say so, loudly.
        late = d["eps_a"] > 1e-3
        lateral = np.stack([-d["sxx"], -d["syy"]])
        target = lateral[:, 0].mean()
        if late.any() and target > 0:
            worst = np.max(np.abs(lateral[:, late] - target)) / target
            if worst > LATERAL_TOLERANCE:
                print(f"WARNING: {label}: the lateral stress strays {100 * worst:.0f} % from "
                      f"{target / 1e3:.0f} kPa: its control failed, the curve is not a drained "
                      "triaxial test at that confinement", file=sys.stderr)
    return d["eps_a"], d["eps_v"], q


def series_of_run(directory, von_mises_mean=False):
    """Sample means of an `mpmxdem run` directory. means.csv holds eps_ax = 1 - F_zz and
    eps_v = 1 - V/V0; the DEM series (mpmxdem dem, triax_dem, YADE) hold logarithmic strains
    -ln(L/L0), -ln(V/V0): converted to those. q = sigma_a - sigma_r of the mean RVE stress
    (results.h5), as in the DEM series; q_mean_Pa of means.csv is the mean von Mises q."""

    d = read_csv(os.path.join(directory, "means.csv"))
    if von_mises_mean:
        return -np.log1p(-d["eps_ax"]), -np.log1p(-d["eps_v"]), d["q_mean_Pa"]
    with readers.results(directory) as f:
        mean = -f["rve/stress"][:].reshape(len(f["time"]), -1, 3, 3).mean(axis=1)
    q = mean[:, 2, 2] - 0.5 * (mean[:, 0, 0] + mean[:, 1, 1])
    return -np.log1p(-d["eps_ax"]), -np.log1p(-d["eps_v"]), q


def is_dem_directory(path):
    return os.path.isfile(os.path.join(path, "dem_series.csv")) and not os.path.isfile(
        os.path.join(path, "means.csv"))


def plot_means(sources, prefix):
    fig, (ax_q, ax_v) = plt.subplots(2, 1, figsize=(7, 8), sharex=True)
    for label, (eps, epsv, q) in sources:
        ax_q.plot(100 * eps, q / 1e3, label=label)
        ax_v.plot(100 * eps, 100 * epsv, label=label)
    ax_q.set_ylabel("q = sigma_a - sigma_r [kPa]")
    ax_v.set_ylabel("eps_v [%] (compression positive)")
    ax_v.set_xlabel("axial strain eps_ax [%]")
    for ax in (ax_q, ax_v):
        ax.grid(True, alpha=0.3)
        ax.legend()
    fig.tight_layout()
    name = prefix + "_q_epsv.png"
    fig.savefig(name, dpi=120)
    print("wrote", name)


def plot_rves(directory, label, prefix, index):

    with readers.results(directory) as f:
        eps = -np.log1p(-f["means/eps_ax"][:])  # logarithmic, as series_of_run
        stress = -f["rve/stress"][:].reshape(len(eps), -1, 3, 3)  # compression positive
        z = f["rve/z"][:]
        ids = f["rve/id"][:]
    principal = np.linalg.eigvalsh(0.5 * (stress + np.swapaxes(stress, -1, -2)))
    lateral = 0.5 * (stress[:, :, 0, 0] + stress[:, :, 1, 1])
    fig, axes = plt.subplots(3, 1, figsize=(7, 10), sharex=True)
    for k, rve in enumerate(ids):
        color = f"C{k % 10}"  # one colour per RVE in every panel
        for c, style in zip(range(3), ("-", "--", ":")):
            axes[0].plot(100 * eps, principal[:, k, c] / 1e3, style, color=color, lw=0.8,
                         label=f"RVE {rve}" if c == 2 else None)
        axes[1].plot(100 * eps, z[:, k], color=color, lw=0.8)
        # An RVE that lost its contacts has no lateral stress: leave those rows out of the ratio.
        ratio = np.where(lateral[:, k] > 1e3, stress[:, k, 2, 2] / np.maximum(lateral[:, k], 1e3), np.nan)
        axes[2].plot(100 * eps, ratio, color=color, lw=0.8)
    axes[0].set_ylabel("principal stresses [kPa]")
    axes[1].set_ylabel("coordination number Z")
    axes[2].set_ylabel("sigma_zz / mean lateral (lateral > 1 kPa)")
    axes[2].set_xlabel("axial strain eps_ax [%]")
    axes[0].legend(fontsize=7, ncol=4)
    axes[0].set_title(label)
    for ax in axes:
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    name = f"{prefix}_rves_{index}.png"
    fig.savefig(name, dpi=120)
    print("wrote", name)


def summary(directory, label):
    """Numbers of docs/validation/triaxial.md: peak q, q and eps_v at 10/20/30 %, lateral stress per RVE."""

    # The q of docs/validation/triaxial.md: the mean over RVEs of their von Mises q (means.csv).
    eps, epsv, q = series_of_run(directory, von_mises_mean=True)
    k = int(np.argmax(q))
    print(f"{label}: peak q (mean von Mises q of the RVEs) {q[k] / 1e3:.1f} kPa at eps_ax {100 * eps[k]:.2f} %")
    for e in (0.10, 0.20, 0.30):
        if eps[-1] >= e - 0.002:  # the last row may stop just short of the target
            at = min(e, eps[-1])
            print(f"  at {100 * at:.1f} %: q {np.interp(at, eps, q) / 1e3:.1f} kPa, eps_v {100 * np.interp(at, eps, epsv):.2f} %")
    with readers.results(directory) as f:
        stress = -f["rve/stress"][:].reshape(len(f["time"]), -1, 3, 3)
        ids = f["rve/id"][:]
    lat = np.stack([stress[:, :, 0, 0], stress[:, :, 1, 1]], axis=-1)  # [row, rve, 2]
    worst = 0.0
    for j, rve in enumerate(ids):
        lo, hi = lat[:, j].min() / 1e3, lat[:, j].max() / 1e3
        worst = max(worst, abs(lo - 100.0), abs(hi - 100.0))
        print(f"  RVE {rve}: lateral stress {lo:.1f} .. {hi:.1f} kPa, at the end {lat[-1, j, 0] / 1e3:.1f} / {lat[-1, j, 1] / 1e3:.1f}")
    print(f"  largest lateral deviation from 100 kPa over all RVEs and rows: {worst:.1f} kPa"
          f" ({'within' if worst <= 5.0 else 'NOT within'} 5 %)")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True, help="prefix of the PNG files")
    ap.add_argument("--run", action="append", default=[], help="mpmxdem run output directory[=label]")
    ap.add_argument("--csv", action="append", default=[], help="series CSV[=label]")
    ap.add_argument("--summary", action="store_true",
                    help="also print, for every --run: peak q, q and eps_v at 10/20/30 %%, lateral stress per RVE")
    a = ap.parse_args()
    if not a.run and not a.csv:
        ap.error("give at least one --run or --csv")
    sources = []
    runs = []
    for arg in a.csv:
        path, label = split_label(arg)
        sources.append((label, series_of_csv(path, label)))
    for arg in a.run:
        path, label = split_label(arg)
        if is_dem_directory(path):  # an `mpmxdem dem` output: its series, no RVEs
            print(f"{path}: an `mpmxdem dem` output; plotting its dem_series.csv", file=sys.stderr)
            sources.append((label, series_of_csv(os.path.join(path, "dem_series.csv"), label)))
        elif not os.path.isfile(os.path.join(path, "means.csv")):
            ap.error(f"--run {path}: neither an `mpmxdem run` output (means.csv, results.h5) nor "
                     "an `mpmxdem dem` output (dem_series.csv)")
        else:
            sources.append((label, series_of_run(path)))
            runs.append(arg)
    plot_means(sources, a.out)
    for i, arg in enumerate(runs):
        path, label = split_label(arg)
        plot_rves(path, label, a.out, i)
        if a.summary:
            summary(path, label)


if __name__ == "__main__":
    sys.exit(main())
