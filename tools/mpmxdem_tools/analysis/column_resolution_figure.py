#!/usr/bin/python3
"""Figure: the a = 2 column's final deposit and its height at the back wall against time, for the
MPM x DEM column at 1 and 2 x 2 points per cell, the Drucker-Prager continuum (phi = 40 deg) at
three resolutions, and the dense pure-DEM (YADE) column. Reads only CSV files of docs/data.

Usage: tools/mpmxdem-tools column_resolution_figure [--data docs/data] [--fig docs/figures]
Writes FIG/column_a2_resolution.png.
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

SERIES = [  # label, directory, file stem, L0 [m], H0 [m], style
    ("pure DEM (YADE), dense, L0 = 14.4 d50", "column_collapse_yade", "dense_a2_n3000_l0.05",
     None, None, dict(color="k", lw=2.0)),
    ("MPM x DEM, 1 point per cell", "column_collapse_mpm", "a2", 0.5, 1.0,
     dict(color="tab:red", ls="--")),
    ("MPM x DEM, 2 x 2 points per cell", "column_collapse_mpm_2x2", "a2", 0.5, 1.0,
     dict(color="tab:red", lw=2.0)),
    ("Drucker-Prager 40 deg, 1 point per cell", "column_collapse_frictional",
     "phi40_ppc1_h0.0625", 0.5, 1.0, dict(color="tab:blue", ls="--")),
    ("Drucker-Prager 40 deg, 2 x 2, h = L0/8", "column_collapse_frictional",
     "phi40_ppc2_h0.0625", 0.5, 1.0, dict(color="tab:blue", lw=2.0)),
    ("Drucker-Prager 40 deg, 2 x 2, h = L0/32", "column_collapse_frictional",
     "phi40_ppc2_h0.015625", 0.5, 1.0, dict(color="tab:cyan", lw=1.5)),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", default="docs/data")
    ap.add_argument("--fig", default="docs/figures")
    args = ap.parse_args()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.2))
    for label, folder, stem, L0, H0, style in SERIES:
        base = os.path.join(args.data, folder, stem)
        if not os.path.exists(base + "_profiles.csv"):
            print("missing", base + "_profiles.csv: skipped")
            continue
        if L0 is None:  # YADE: its own column size
            s = pd.read_csv(base + "_summary.csv").iloc[0]
            L0, H0 = float(s["L0_m"]), float(s["H0_m"])
        prof = pd.read_csv(base + "_profiles.csv")
        last = prof[prof["t_over_tstar"].astype(str) == "final"]
        if last.empty:
            tt = pd.to_numeric(prof["t_over_tstar"], errors="coerce")
            last = prof[tt == tt.max()]
        ax1.plot(last["x_m"] / L0, last["h_vol_m"] / H0, label=label, **style)
        ts = pd.read_csv(base + "_timeseries.csv")
        hcol = "H_back_m" if "H_back_m" in ts else "H_m"
        if hcol in ts:
            ax2.plot(ts["t_over_tstar"], ts[hcol] / (H0 if hcol == "H_back_m" else ts[hcol].iloc[0]),
                     **style)
    ax1.axvline(1.0, color="0.6", lw=0.8)
    ax1.set_xlabel("x / L0")
    ax1.set_ylabel("deposit height (at the initial density) / H0")
    ax1.set_xlim(0, 4.5)
    ax1.set_ylim(0, 1.05)
    ax1.legend(fontsize=7)
    ax1.set_title("a = 2: final deposit")
    ax2.set_xlabel("t / t*")
    ax2.set_ylabel("height at the back wall / H0")
    ax2.set_xlim(0, 10)
    ax2.set_ylim(0, 1.05)
    ax2.set_title("a = 2: height at the back wall")
    fig.tight_layout()
    os.makedirs(args.fig, exist_ok=True)
    out = os.path.join(args.fig, "column_a2_resolution.png")
    fig.savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    main()
