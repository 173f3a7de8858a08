#!/usr/bin/env python3
"""Checks the platen reaction of a single-cell triaxial run (issue 15.3): reactions.csv (pandas)
and /constraints of results.h5 (h5py) agree, and the platen's R_z follows the points' mean
sigma_zz times the current area A = V / H, times H / h: the internal force integrates sigma over
V / h (h: the cell, H = h + u_platen - u_base: the material's height), so R = sum_p V_p
sigma_zz,p / h for a constant platen velocity, i.e. mean(sigma_zz) A H / h when the points'
volumes are equal. Against mean(sigma_zz) A alone the difference is H / h - 1 (the axial strain).

Usage: check_reactions.py RUN_DIR PLATEN BASE TOLERANCE   (exit 77 without h5py: skipped)
"""
import sys

try:
    import h5py
    import numpy as np
except ImportError:
    print("h5py/numpy not available: skipped")
    sys.exit(77)

run, platen, base, tol = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
with h5py.File(f"{run}/results.h5", "r") as f:
    names = f["constraints"].attrs["names"].split(",")
    k = names.index(platen)
    reaction = f["constraints/reaction"][:, k, :]
    disp = f["constraints/displacement"][:, k, :]
    disp_base = f["constraints/displacement"][:, names.index(base), :]
    volume = f["points/volume"][:]
    szz = f["points/stress"][:, :, 8]
    time = f["time"][:]
    assert f["constraints/reaction"].attrs["unit"] == "N"
    assert f["constraints/displacement"].attrs["unit"] == "m"

try:
    import pandas as pd
    csv = pd.read_csv(f"{run}/reactions.csv", float_precision="round_trip")
    rz = csv[f"{platen}_rz_N"].to_numpy()
    uz = csv[f"{platen}_uz_m"].to_numpy()
except ImportError:
    import csv as csvmod
    with open(f"{run}/reactions.csv") as fh:
        rows = list(csvmod.DictReader(fh))
    rz = np.array([float(r[f"{platen}_rz_N"]) for r in rows])
    uz = np.array([float(r[f"{platen}_uz_m"]) for r in rows])
if not (np.array_equal(rz, reaction[:, 2]) and np.array_equal(uz, disp[:, 2])):
    sys.exit("reactions.csv and results.h5 /constraints differ")

h = 1.0  # one cell of 1 m (the jobs checked)
height = h + disp[:, 2] - disp_base[:, 2]
area = volume.sum(axis=1) / height
expected = szz.mean(axis=1) * area * height / h
plain = szz.mean(axis=1) * area
rows = slice(1, None)  # row 0: before the first step (no reaction yet)
err = np.abs(reaction[rows, 2] / expected[rows] - 1.0)
err_plain = np.abs(reaction[rows, 2] / plain[rows] - 1.0)
print(f"{platen}: {len(err)} rows, t = {time[-1]:.4g} s, R_z = {reaction[-1, 2]:.6g} N, "
      f"mean sigma_zz A H/h = {expected[-1]:.6g} N: max rel. error {err.max():.3e} "
      f"(against sigma_zz A alone: {err_plain.max():.3e}); u_z = {disp[-1, 2]:.6g} m")
if not err.max() < tol:
    sys.exit(f"platen reaction off the mean sigma_zz times area by {err.max():.3e} > {tol}")
