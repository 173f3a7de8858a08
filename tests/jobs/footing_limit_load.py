#!/usr/bin/python3
"""The strip footing to its limit load, on the Drucker-Prager continuum (tools/mpmxdem_tools/jobs/footing_make_job.py
--material frictional: plane-strain Mohr-Coulomb, phi = 40 deg, no dilatancy), 200 x 100 mm on
12.5 mm cells, pushed to s/B = 0.4 by the staircase of held planes (three boxes), with the job's
Cundall damping 0.2 (without it, each plane the staircase takes over rings: the load dips by up to
70 % and the reactions miss equilibrium by tens of % for a while; tests/jobs/footing_equilibrium.py
checks equilibrium on one plane). Checks, against theory no one here wrote, that
- the limit load (the mean bearing pressure over s/B in [0.3, 0.4]) lies between Davis's
  non-associated estimate q0 N_q(phi*), tan phi* = sin phi (psi = 0), and Prandtl's associated
  q0 N_q(phi) (tools/mpmxdem_tools/analysis/bearing_capacity.py): 1.26 and 3.21 MPa. Measured: 2.07 MPa (phi mobilised
  36.7 deg); an elastic layer, a plasticity that does not yield or a staircase that loses the
  footing's grip leaves that band.

    footing_limit_load.py MPIEXEC EXE OUTDIR
"""
import sys

import footing_run  # also puts tools/ on the path
from mpmxdem_tools.analysis import bearing_capacity  # noqa: E402 (tools/, put on the path by footing_run)
from mpmxdem_tools.jobs import footing_make_job  # noqa: E402 (tools/, put on the path by footing_run)

PHI = 40.0


def main():
    mpiexec, exe, out = sys.argv[1:4]
    p = dict(footing_make_job.DEFAULTS, settlement=0.02, material="frictional",
             friction_angle=PHI, every=20)
    sb, q, footing = footing_run.run_curve(mpiexec, exe, out, p)
    if len(footing) < 3:
        sys.exit("expected a staircase of 3 boxes to s/B = 0.4, got %s" % footing)
    q_lim = footing_run.mean_over(sb, q, 0.3, 0.4)
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
