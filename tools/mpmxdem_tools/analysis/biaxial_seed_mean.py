#!/usr/bin/python3
"""The mean pure-DEM response of the RVE samples an MPM x DEM job uses: the per-sample series of
`mpmxdem dem` (dem_series.csv of each seed) averaged on a common axial-strain grid, written as one
series with the columns tools/mpmxdem_tools/analysis/biaxial_analysis.py reads (eps_a, eps_v, sig_a, sig_r), so that it
can stand as the reference (`--dem MEAN.csv:label`). docs/validation/biaxial.md, "Which pure DEM".

  tools/mpmxdem-tools biaxial_seed_mean OUT.csv SERIES.csv [SERIES.csv ...] [--step 2.5e-4]

The mean is of the stress ratio sigma_a / sigma_r (each sample's servo holds sigma_r at its own
small error) and of eps_v; sig_r is written as the confining pressure (100 kPa) and sig_a as the
mean ratio times it. Printed: the mean and range of the ratio at a few strains, each sample's peak.
"""
import argparse
import sys

import numpy as np
import pandas as pd

P_CONF = 1e5


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("series", nargs="+")
    ap.add_argument("--step", type=float, default=2.5e-4, help="strain grid step [-]")
    a = ap.parse_args()
    curves = []
    for path in a.series:
        d = pd.read_csv(path)
        d = d[d["eps_a"] > 0.0]
        curves.append((d["eps_a"].to_numpy(), (d["sig_a"] / d["sig_r"]).to_numpy(),
                       d["eps_v"].to_numpy()))
    top = min(c[0][-1] for c in curves)
    grid = np.arange(a.step, top + 1e-12, a.step)
    ratio = np.array([np.interp(grid, e, r) for e, r, _ in curves])
    eps_v = np.array([np.interp(grid, e, v) for e, _, v in curves])
    mean = ratio.mean(axis=0)
    pd.DataFrame({"eps_a": grid, "eps_v": eps_v.mean(axis=0), "sig_a": mean * P_CONF,
                  "sig_r": np.full_like(grid, P_CONF), "ratio_min": ratio.min(axis=0),
                  "ratio_max": ratio.max(axis=0), "ratio_std": ratio.std(axis=0, ddof=1)
                  if len(curves) > 1 else np.zeros_like(grid)}).to_csv(a.out, index=False)
    print(f"{len(curves)} samples, common strain range to {100 * top:.2f} %; written {a.out}")
    for eps in (0.0025, 0.005, 0.01, 0.015, 0.02, 0.03, 0.04):
        if eps > top:
            break
        col = ratio[:, int(round(eps / a.step)) - 1]
        print(f"  eps_a {100 * eps:4.2f} %: mean ratio {col.mean():7.3f}  range {col.min():.3f}-"
              f"{col.max():.3f}  std {col.std(ddof=1) if len(col) > 1 else 0.0:.3f}")
    k = int(np.argmax(mean))
    print(f"  peak of the mean: {mean[k]:.3f} at {100 * grid[k]:.2f} %; samples' own peaks "
          f"{', '.join(f'{r.max():.2f}' for r in ratio)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
