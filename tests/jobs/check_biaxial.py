#!/usr/bin/python3
"""Checks a small plane-strain biaxial run (tests/jobs/biaxial_small.toml) against equilibrium:

  check_biaxial.py RUN_DIR BAND R_TOL BASE_TOL

From 0.25 % axial strain on (the start from rest at a constant platen speed is dynamic):
- the side tractions hold the lateral stress: the volume mean of the points' sigma_xx within BAND
  (a fraction) of the side pressure (exact in equilibrium for straight sides and smooth platens:
  int sigma_xx dV = -p (x+ - x-) H T);
- the platen reaction equals the integrated point stress: -R_z(platens) H_current within R_TOL of
  -sum_p V_p sigma_zz,p (int sigma_zz dV = int z t_z dA: only the top platen, at z = H_current,
  contributes); the base reaction balances the platen's within BASE_TOL (the difference is the
  scaled inertia and damping of a dynamic scheme).
Exit 0 pass, 1 fail, 77 without h5py.
"""
import os
import sys
import tomllib

try:
    import h5py
    import numpy as np
except ImportError:
    sys.exit(77)


def main():
    run, band, r_tol, base_tol = sys.argv[1], *(float(v) for v in sys.argv[2:5])
    with open(os.path.join(run, "job.toml"), "rb") as f:
        job = tomllib.load(f)
    body = job["mpm"]["body"][0]
    H = body["max"][2] - body["min"][2]
    p = float(job["mpm"]["traction"][0]["pressure"].split()[0]) * 1e3  # "100 kPa"
    f = h5py.File(os.path.join(run, "results.h5"), "r")
    names = f["constraints"].attrs["names"]
    names = (names.decode() if isinstance(names, bytes) else names).split(",")
    platens = [k for k, n in enumerate(names) if n.startswith("platen")]
    base = names.index("base")
    R = f["constraints/reaction"][:]
    D = f["constraints/displacement"][:]
    vol = f["points/volume"][:]
    st = f["points/stress"][:].reshape(len(vol), -1, 3, 3)
    eps = -np.log(1.0 + D[:, platens[0], 2] / H)
    ok = True
    rows = np.nonzero(eps >= 0.0025)[0]
    if rows.size < 3 or eps[-1] < 0.0095:
        print(f"FAIL: the run reached eps_a = {eps[-1]:.4f} ({rows.size} rows past 0.25 %)")
        return 1
    worst = {"lateral": 0.0, "integrated": 0.0, "base": 0.0}
    for i in rows:
        sxx = -(vol[i] * st[i, :, 0, 0]).sum() / vol[i].sum()
        szz_int = -(vol[i] * st[i, :, 2, 2]).sum()
        rz = -R[i, platens, 2].sum()
        h_cur = H + D[i, platens[0], 2]
        e_lat = abs(sxx / p - 1.0)
        e_int = abs(rz * h_cur / szz_int - 1.0)
        e_base = abs((R[i, base, 2] - rz) / rz)
        for k, v in (("lateral", e_lat), ("integrated", e_int), ("base", e_base)):
            worst[k] = max(worst[k], v)
        print(f"eps_a {100 * eps[i]:.3f} %: mean sigma_xx {sxx / 1e3:.2f} kPa ({100 * e_lat:.2f} %), "
              f"platen R_z H {rz * h_cur:.4g} vs int sigma_zz dV {szz_int:.4g} ({100 * e_int:.2f} %), "
              f"base {R[i, base, 2]:.4g} N vs platen {rz:.4g} N ({100 * e_base:.2f} %)")
    print(f"worst: lateral {100 * worst['lateral']:.2f} % (band {100 * band:.1f} %), platen vs "
          f"integrated stress {100 * worst['integrated']:.2f} %, base vs platen "
          f"{100 * worst['base']:.2f} % (tolerances {100 * r_tol:.1f} %, {100 * base_tol:.1f} %)")
    if worst["lateral"] > band:
        print("FAIL: the side tractions do not hold the lateral stress")
        ok = False
    if worst["integrated"] > r_tol:
        print("FAIL: the platen reaction does not match the integrated point stress")
        ok = False
    if worst["base"] > base_tol:
        print("FAIL: the base reaction does not balance the platen's")
        ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
