"""Checks a run of jobs/geostatic_column_small.toml (issue 15): the points start at their in-situ
stress and stay there after settling. Usage: check_geostatic.py RUN_DIR RHO K0 SURFACE_Z
Exit 77 (skipped) without h5py.

- Start (row 0, step 0): every point's stress is its RVE's (bit for bit: the scene starts from the
  RVEs' stresses), and within the servo tolerance of 1 % (dem.initial_state.stress_tolerance =
  0.01 of the job, group_tolerance 0.01 adds nothing: one group per depth) of its target:
  sigma_zz = -rho g depth, sigma_xx = sigma_yy = K0 sigma_zz each within 1 % of itself,
  off-diagonal components within 1 % of p.
- After settling (last row): sigma_v within 2 % of rho g depth and sigma_h / sigma_v within 5 % of
  K0 at every point, and the reaction of the rigid rough base (constraint "base") equal to the
  column's weight within 0.5 % (the issue's tolerances for the geostatic column).
"""
import sys

try:
    import h5py
    import numpy as np
except ImportError:
    print("h5py or numpy missing: skipped")
    sys.exit(77)

run, rho, k0, top = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
g = 9.81
f = h5py.File(run + "/results.h5", "r")
x0 = f["points/x"][0]
depth = top - x0[:, 2]
fails = []


def check(cond, what):
    if not np.all(cond):
        fails.append(what)


# The points' start stress is their RVE's.
pid = f["points/id"][:]
rid = list(f["rve/id"][:])
ps = f["points/stress"][0]
rs = f["rve/stress"][0]
check(np.array_equal(ps, rs[[rid.index(i) for i in pid]]), "points/stress != rve/stress at step 0")

for row, tol_v, tol_k, tol_off, name in ((0, 0.01, None, 0.01, "start"),
                                         (-1, 0.02, 0.05, None, "settled")):
    s = f["points/stress"][row].reshape(-1, 3, 3)
    sv = -rho * g * depth
    ratio_v = s[:, 2, 2] / sv
    k = 0.5 * (s[:, 0, 0] + s[:, 1, 1]) / s[:, 2, 2]
    p = -np.trace(s, axis1=1, axis2=2) / 3.0
    off = np.abs(s[:, [0, 0, 1], [1, 2, 2]]).max(axis=1) / p
    print(f"{name} (t = {f['time'][row]:.4g} s): sigma_v / (rho g depth) in "
          f"[{ratio_v.min():.4f}, {ratio_v.max():.4f}], K0 in [{k.min():.4f}, {k.max():.4f}], "
          f"max |off-diagonal| / p = {off.max():.4f}")
    check(np.abs(ratio_v - 1.0) <= tol_v, f"{name}: sigma_v beyond {tol_v} of rho g depth")
    if tol_k is None:  # each lateral component within the servo tolerance of its target
        for a in (0, 1):
            check(np.abs(s[:, a, a] / (k0 * sv) - 1.0) <= 0.01, f"{name}: sigma_{a}{a} beyond 1 %")
    else:
        check(np.abs(k / k0 - 1.0) <= tol_k, f"{name}: K0 beyond {tol_k}")
    if tol_off is not None:
        check(off <= tol_off, f"{name}: off-diagonal stress beyond {tol_off} p")

# The rigid rough base (the constraint named "base") carries the column's weight once it has settled:
# the lateral walls are smooth (x or y held only), the internal forces sum to zero over the nodes, so
# R_z = M g - M a_z; 0.5 % is the tolerance (measured: under 1e-5).
names = f["constraints"].attrs["names"]  # comma-separated, as the columns of reactions.csv
names = (names.decode() if isinstance(names, bytes) else str(names)).split(",")
weight = rho * g * f["points/volume"][0].sum()  # mass = rho V0
r_base = f["constraints/reaction"][-1, names.index("base"), 2]
print(f"base reaction {r_base:.6g} N against the weight {weight:.6g} N "
      f"(relative difference {r_base / weight - 1.0:.2e})")
check(abs(r_base / weight - 1.0) <= 0.005, "base reaction beyond 0.5 % of the weight")

if fails:
    print("FAILED:\n  " + "\n  ".join(fails))
    sys.exit(1)
print("geostatic column: OK")
