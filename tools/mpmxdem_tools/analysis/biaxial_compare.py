#!/usr/bin/python3
"""Biaxial runs against a pure-DEM reference at fixed axial strains (docs/validation/biaxial.md, "Which pure
DEM"): for each run, in % against the reference's sigma_a / sigma_r, (1) the global ratio
(int sigma_zz dV / (H A)) / 100 kPa and (2) the ratio of the volume means sigma_zz / sigma_xx (the
specimen's average element), and the volume-mean sigma_xx [kPa].

  tools/mpmxdem-tools biaxial_compare --dem REF.csv RUN_DIR[:label] ... [--strains 0.0025,0.005,...]
"""
import argparse
import sys

import numpy as np

from . import biaxial_analysis as B  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--dem", required=True, help="reference series (dem_series.csv columns)")
    ap.add_argument("--strains", default="0.0025,0.005,0.01,0.015,0.02,0.025,0.03")
    a = ap.parse_args()
    ref = B.dem_series(a.dem)
    pts = [float(x) for x in a.strains.split(",")]
    at = lambda e, y, p: np.interp(p, e, y)  # noqa: E731
    print("| run | " + " | ".join(f"{100 * p:g} %" for p in pts) + " | ratio of means | mean sigma_xx [kPa] |")
    print("|---|" + "---|" * (len(pts) + 2))
    print("| reference sigma_a/sigma_r | " + " | ".join(f"{at(ref['eps'], ref['ratio'], p):.2f}" for p in pts) + " | | |")
    for spec in a.runs:
        path, _, label = spec.partition(":")
        r = B.Run(path, label or None)
        rel = lambda y, p: (f"{100 * (at(r.eps, y, p) / at(ref['eps'], ref['ratio'], p) - 1):+.1f}"  # noqa: E731
                            if p <= r.eps[-1] else "-")
        means = r.sig_mean[:, 2, 2] / r.sig_mean[:, 0, 0]
        sxx = r.sig_mean[:, 0, 0] / 1e3
        print(f"| {label or path} | " + " | ".join(rel(r.ratio, p) for p in pts) + " | "
              + " / ".join(rel(means, p) for p in pts) + " | "
              + " / ".join(f"{at(r.eps, sxx, p):.0f}" if p <= r.eps[-1] else "-" for p in pts) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
