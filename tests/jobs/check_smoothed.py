#!/usr/bin/env python3
"""Issue 18's suite check of strain smoothing: the smoothed single cell of
jobs/triaxial_mpmxdem_smoothed_small.toml keeps every RVE's lateral stress within BAND of the
confining pressure, their spread (largest minus smallest RVE at a row, over the confining
pressure) stays within SPREAD, and its q (of the mean RVE stress) stays within Q_TOL of the pure DEM of the
same packing (jobs/triaxial_dem_small.toml), as an RMS over eps_ax in [0.2 %, EPS_MAX] divided by
the DEM's largest q there.

Usage: check_smoothed.py RUN_DIR DEM_SERIES_CSV BAND SPREAD Q_TOL [PRESSURE_PA]
Exit 0: both hold; 1: one does not (the figures are printed either way)."""
import os
import sys

import numpy as np

try:
    import h5py
except ImportError:  # the test is skipped (SKIP_RETURN_CODE 77), not failed
    print("h5py not installed: check skipped")
    sys.exit(77)


def main():
    run, dem_csv = sys.argv[1], sys.argv[2]
    band, spread_tol, q_tol = (float(a) for a in sys.argv[3:6])
    p0 = float(sys.argv[6]) if len(sys.argv) > 6 else 1e5
    with h5py.File(os.path.join(run, "results.h5"), "r") as f:
        rows = len(f["time"])
        stress = -f["rve/stress"][:].reshape(rows, -1, 3, 3)  # compression positive
        eps_ax = -np.log1p(-f["means/eps_ax"][:])  # logarithmic, as the DEM series
    lateral = np.stack([stress[:, :, 0, 0], stress[:, :, 1, 1]], axis=-1)
    dev = np.abs(lateral / p0 - 1.0).max()
    print(f"lateral stress of {stress.shape[1]} RVEs over {rows} rows: "
          f"{lateral.min() / 1e3:.2f} .. {lateral.max() / 1e3:.2f} kPa, "
          f"largest deviation {100 * dev:.2f} % (band {100 * band:.2f} %)")
    spread = (lateral.max(axis=1) - lateral.min(axis=1)).max() / p0
    print(f"largest spread of the RVEs' lateral stresses at a row: {100 * spread:.3f} % "
          f"(tolerance {100 * spread_tol:.2f} %)")
    mean = stress.mean(axis=1)
    q = mean[:, 2, 2] - 0.5 * (mean[:, 0, 0] + mean[:, 1, 1])
    dem = np.genfromtxt(dem_csv, delimiter=",", names=True)
    lo, hi = 0.002, min(eps_ax[-1], dem["eps_a"][-1])
    sel = (eps_ax >= lo) & (eps_ax <= hi)
    if sel.sum() < 5:
        print(f"too few rows in [{lo}, {hi}]: {sel.sum()}")
        return 1
    q_dem = np.interp(eps_ax[sel], dem["eps_a"], dem["q"])
    scale = dem["q"][(dem["eps_a"] >= lo) & (dem["eps_a"] <= hi)].max()
    rms = np.sqrt(np.mean((q[sel] - q_dem) ** 2)) / scale
    print(f"q against pure DEM over eps_ax [{100 * lo:.1f} %, {100 * hi:.2f} %] ({sel.sum()} rows): "
          f"RMS {100 * rms:.2f} % of the DEM's largest q {scale / 1e3:.1f} kPa "
          f"(tolerance {100 * q_tol:.1f} %); coupled q at the end {q[-1] / 1e3:.1f} kPa, "
          f"DEM {np.interp(eps_ax[-1], dem['eps_a'], dem['q']) / 1e3:.1f} kPa")
    ok = dev <= band and spread <= spread_tol and rms <= q_tol
    print("OK" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
