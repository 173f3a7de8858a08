#!/usr/bin/python3
"""Errors of MPM x DEM triaxial runs against reference series (docs/validation/triaxial.md sections 6-7).

Usage (from the repository, /usr/bin/python3 for h5py):
  tools/mpmxdem-tools triaxial_errors RUN_DIR[=label]... [--reference CSV[=label]]... [--strain 0.30]

For each run and reference: RMS of the relative q error over eps_ax in [0.2 %, strain] on the
reference's rows, peak q relative to the reference's, RMS of the eps_v difference (percentage
points) over the same rows, as tools/mpmxdem_tools/bench/bench_speed_error.py computes them (q = sigma_a - sigma_r of
the mean RVE stress; logarithmic strains, compression positive). Then, per run, the range of
every RVE's lateral stresses (sigma_xx and sigma_yy, compression positive) over all rows, the
largest spread between the RVEs at one row, and the axial strain up to which every RVE stays
within 5 % of 100 kPa.
Default reference: the 30,000-sphere pure DEM of docs/data/triaxial_dem_30k.
"""
import argparse
import math
import os

import numpy as np

from .plot_triaxial import series_of_csv, series_of_run, split_label  # noqa: E402

from .. import readers
from ..paths import ROOT as REPO

REF_30K = os.path.join(REPO, "docs", "data", "triaxial_dem_30k", "dem_series.csv")
EPS_LO = 0.002  # as tools/mpmxdem_tools/bench/bench_speed_error.py: q ~ 0 before, relative errors undefined
P0 = 100.0  # confining pressure [kPa]


def errors(run, ref, strain):
    eps, epsv, q = run
    reps, repsv, rq = ref
    rows = (reps >= EPS_LO) & (reps <= min(strain, eps[-1]))
    grid = reps[rows]
    qi = np.interp(grid, eps, q)
    rms_q = math.sqrt(np.mean(((qi - rq[rows]) / rq[rows]) ** 2))
    rms_v = math.sqrt(np.mean((np.interp(grid, eps, epsv) - repsv[rows]) ** 2))
    peak = q[eps <= strain].max() / rq[reps <= strain].max() - 1.0
    return rms_q, peak, rms_v


def lateral(directory):

    with readers.results(directory) as f:
        stress = -f["rve/stress"][:].reshape(len(f["time"]), -1, 3, 3) / 1e3  # kPa, compression +
        eps = -np.log1p(-f["means/eps_ax"][:])
    lat = np.stack([stress[:, :, 0, 0], stress[:, :, 1, 1]], axis=-1)  # [row, rve, 2]
    spread = (lat.max(axis=(1, 2)) - lat.min(axis=(1, 2))).max()
    out = np.abs(lat / P0 - 1.0).max(axis=(1, 2)) > 0.05
    held_to = eps[np.argmax(out)] if out.any() else eps[-1]
    return lat.min(), lat.max(), spread, held_to, out.any()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--reference", action="append", default=[])
    ap.add_argument("--strain", type=float, default=0.30)
    a = ap.parse_args()
    refs = [split_label(r) for r in (a.reference or [REF_30K + "=30k DEM"])]
    for arg in a.runs:
        path, label = split_label(arg)
        run = series_of_run(path)
        print(f"{label} ({path}): reached eps_ax {100 * run[0][-1]:.1f} %")
        for rpath, rlabel in refs:
            rms_q, peak, rms_v = errors(run, series_of_csv(rpath, rlabel), a.strain)
            print(f"  vs {rlabel}: q RMS {100 * rms_q:.1f} %, peak q {100 * peak:+.1f} %, "
                  f"eps_v RMS {100 * rms_v:.2f} %")
        lo, hi, spread, held_to, left = lateral(path)
        print(f"  RVE lateral stresses {lo:.1f} .. {hi:.1f} kPa, largest spread {spread:.1f} kPa, "
              + (f"every RVE within 5 % of {P0:.0f} kPa up to eps_ax {100 * held_to:.2f} %" if left
                 else f"every RVE within 5 % of {P0:.0f} kPa over the whole run"))


if __name__ == "__main__":
    main()
