#!/usr/bin/python3
"""The strip footing on the associated Drucker-Prager continuum (psi = phi = 40 deg), for which
Prandtl's q0 N_q(phi) is the exact limit load of the weightless layer: what is left between them is
the MPM's own error. The family's settings (tools/mpmxdem_tools/analysis/footing_family.py ASSOCIATED: E = 500 MPa, mass
scaling 1e3, to s/B = 0.06), on 400 x 200 mm with 25 mm cells (the footing two cells wide, 512
points). Checks that the limit load (the mean bearing pressure over s/B in [0.02, 0.06]) is
Prandtl's 3.21 MPa within 10 %: this coarsest mesh of docs/validation/footing.md gives 3.01 MPa
(-6.4 %, the same as on the 800 x 400 mm layer, where 12.5 and 6.25 mm cells give +0.6 and +6.2 %). The same run without
dilatancy (psi = 0) gives 2.59 MPa (-19 %), and with a cone not matched to plane strain for psi = phi
(eta = sin phi, the cone of psi = 0 with an associated flow) 4.81 MPa (+50 %): both fail.

    footing_associated.py MPIEXEC EXE OUTDIR
"""
import sys

import footing_run  # also puts tools/ on the path
from mpmxdem_tools.analysis import bearing_capacity  # noqa: E402 (tools/, put on the path by footing_run)
from mpmxdem_tools.analysis import footing_family  # noqa: E402 (tools/, put on the path by footing_run)
from mpmxdem_tools.jobs import footing_make_job  # noqa: E402 (tools/, put on the path by footing_run)

TOLERANCE = 0.10


def main():
    mpiexec, exe, out = sys.argv[1:4]
    p = dict(footing_make_job.DEFAULTS, every=20, width=0.4, depth=0.2, cell=0.025, above=2)
    p.update(footing_family.ASSOCIATED)
    phi = p["friction_angle"]
    assert p["dilatancy_angle"] == phi
    sb, q, _ = footing_run.run_curve(mpiexec, exe, out, p)
    q_lim = footing_run.mean_over(sb, q, *footing_family.WINDOWS["associated"])
    prandtl = p["pressure"] * bearing_capacity.n_q(phi)
    print("associated limit load %.4g MPa against Prandtl's %.4g MPa: %+.1f %% (tolerance %g %%)"
          % (q_lim / 1e6, prandtl / 1e6, 100 * (q_lim / prandtl - 1), 100 * TOLERANCE))
    if abs(q_lim / prandtl - 1) > TOLERANCE:
        sys.exit("the associated limit load is not Prandtl's within %g %%" % (100 * TOLERANCE))


if __name__ == "__main__":
    main()
