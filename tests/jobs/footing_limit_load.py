#!/usr/bin/python3
"""The strip footing to its limit load, on the Drucker-Prager continuum (tools/footing_make_job.py
--material frictional: plane-strain Mohr-Coulomb, phi = 40 deg, no dilatancy), 200 x 100 mm on
12.5 mm cells, pushed to s/B = 0.4 by the staircase of held planes (three boxes), with the job's
Cundall damping 0.2 (without it, each plane the staircase takes over rings: the load dips by up to
70 % and the reactions miss equilibrium by tens of % for a while; tests/jobs/footing_equilibrium.py
checks equilibrium on one plane). Checks, against theory no one here wrote, that
- the limit load (the mean bearing pressure over s/B in [0.3, 0.4]) lies between Davis's
  non-associated estimate q0 N_q(phi*), tan phi* = sin phi (psi = 0), and Prandtl's associated
  q0 N_q(phi) (tools/bearing_capacity.py): 1.26 and 3.21 MPa. Measured: 2.07 MPa (phi mobilised
  36.7 deg); an elastic layer, a plasticity that does not yield or a staircase that loses the
  footing's grip leaves that band.

    footing_limit_load.py MPIEXEC EXE OUTDIR
"""
import csv
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import bearing_capacity  # noqa: E402
import footing_make_job  # noqa: E402

PHI = 40.0


def main():
    mpiexec, exe, out = sys.argv[1:4]
    os.makedirs(out, exist_ok=True)
    p = dict(footing_make_job.DEFAULTS, settlement=0.02, material="frictional",
             friction_angle=PHI, every=20)
    job = os.path.join(out, "footing.toml")
    with open(job, "w") as f:
        f.write(footing_make_job.job_text(**p))
    run = os.path.join(out, "run")
    subprocess.run([mpiexec, "-n", "2", exe, "run", job, "--out", run, "--force"], check=True)
    with open(os.path.join(run, "reactions.csv")) as f:
        rows = list(csv.DictReader(f))
    cols = rows[0].keys()
    footing = [c[:-len("_rz_N")] for c in cols if re.fullmatch(r"footing(_\d+)?_rz_N", c)]
    if len(footing) < 3:
        sys.exit("expected a staircase of 3 boxes to s/B = 0.4, got %s" % footing)
    half, thick = p["half_width"], p["cell"]
    sb, q = [], []
    for r in rows:
        sb.append(-float(r["footing_uz_m"]) / (2 * half))
        q.append(-sum(float(r[n + "_rz_N"]) for n in footing) / (half * thick))
    window = [qi for si, qi in zip(sb, q) if 0.3 <= si <= 0.4 + 1e-9]
    if not window or max(sb) < 0.399:
        sys.exit("the footing did not reach s/B = 0.4 (%.3f)" % max(sb))
    q_lim = sum(window) / len(window)
    q0 = p["pressure"]
    lo = q0 * bearing_capacity.n_q(bearing_capacity.davis_angle(PHI, 0.0))
    hi = q0 * bearing_capacity.n_q(PHI)
    phi_mob = bearing_capacity.effective_angle(q_lim / q0)
    print("limit load %.4g MPa (phi mobilised %.2f deg) between Davis %.4g and Prandtl %.4g MPa?"
          % (q_lim / 1e6, phi_mob, lo / 1e6, hi / 1e6))
    if not lo < q_lim < hi:
        sys.exit("the limit load %.4g MPa is outside [%.4g, %.4g] MPa" % (q_lim / 1e6, lo / 1e6, hi / 1e6))


if __name__ == "__main__":
    main()
