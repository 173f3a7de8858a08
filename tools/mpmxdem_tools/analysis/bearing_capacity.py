#!/usr/bin/python3
"""Bearing-capacity theory for the weightless strip footing under a surcharge (the footing of
tools/mpmxdem-tools footing_make_job and docs/validation/footing.md): Prandtl's limit load and the angles a
measured limit load is read against.

- Prandtl (1921) and Reissner (1924), a rigid-plastic Mohr-Coulomb material with an associated
  flow rule, weightless, cohesionless, surcharge q0 beside the footing:
      q_u = q0 N_q,  N_q(phi) = exp(pi tan phi) tan^2(pi/4 + phi/2)
  (rough or smooth footing alike). Textbook values: N_q(30 deg) = 18.40, N_q(40 deg) = 64.20
  (e.g. Das, Principles of Foundation Engineering, table of Vesic's factors).
- Davis (1968) for a non-associated material (dilatancy psi < phi): the same formula with the
  reduced angle tan phi* = sin phi cos psi / (1 - sin phi sin psi) (for psi = 0: tan phi* = sin
  phi). It is a lower estimate: finite-element limit loads of non-associated Mohr-Coulomb lie
  between q0 N_q(phi*) and q0 N_q(phi).
- The effective angle a measured limit load mobilises: the phi whose N_q(phi) = q_u / q0.
- The size of Prandtl's mechanism under a rough footing of half-width b: an active wedge under the
  footing (base angles pi/4 + phi/2), a log-spiral fan about the footing's edge, r = r0 exp(theta
  tan phi), r0 = b / cos(pi/4 + phi/2), over pi/2, and a passive wedge that reaches the surface
  2 r1 cos(pi/4 - phi/2) beyond the edge (r1 the fan's last radius); its deepest point is the fan's
  at theta = pi/4 + phi/2, r cos(phi) down. At phi = 0: B beyond the edge, B / sqrt(2) deep. A layer
  narrower than the reach cuts the mechanism (its limit load rises).

    tools/mpmxdem-tools bearing_capacity --phi 40 [--psi 0] [--q0 50e3]   # the theory's numbers
    tools/mpmxdem-tools bearing_capacity --effective 40.0               # phi of N_q = 40
    tools/mpmxdem-tools bearing_capacity --phi 40 --half-width 0.025    # and the mechanism's size
    tools/mpmxdem-tools bearing_capacity --self-test                    # (ctest)
"""
import argparse
import math


def n_q(phi_deg):
    """Prandtl's N_q of a friction angle [deg]."""
    t = math.radians(phi_deg)
    return math.exp(math.pi * math.tan(t)) * math.tan(math.pi / 4 + t / 2) ** 2


def davis_angle(phi_deg, psi_deg):
    """Davis's reduced friction angle [deg] of a material with friction phi and dilatancy psi."""
    s, p = math.sin(math.radians(phi_deg)), math.radians(psi_deg)
    return math.degrees(math.atan(s * math.cos(p) / (1.0 - s * math.sin(p))))


def effective_angle(nq):
    """The friction angle [deg] whose N_q is nq (N_q grows monotonically from 1 at 0 deg)."""
    if nq < 1.0:
        raise ValueError("N_q = %g is below 1 (phi = 0)" % nq)
    lo, hi = 0.0, 89.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if n_q(mid) < nq else (lo, mid)
    return 0.5 * (lo + hi)


def mechanism(phi_deg, half_width):
    """Prandtl's mechanism under a rough strip footing of half-width b [m]: (reach beyond the
    footing's edge along the surface, depth below the footing's base) [m]."""
    t = math.radians(phi_deg)
    r0 = half_width / math.cos(math.pi / 4 + t / 2)
    r1 = r0 * math.exp(math.pi / 2 * math.tan(t))
    reach = 2 * r1 * math.cos(math.pi / 4 - t / 2)
    deepest = r0 * math.exp((math.pi / 4 + t / 2) * math.tan(t)) * math.cos(t)
    return reach, max(deepest, half_width * math.tan(math.pi / 4 + t / 2))


def self_test():
    # Textbook values of N_q (Vesic's table, as printed to two decimals).
    for phi, want in ((0, 1.00), (20, 6.40), (30, 18.40), (40, 64.20), (45, 134.87)):
        assert abs(n_q(phi) - want) < 0.006 * want + 0.005, (phi, n_q(phi), want)
    # Davis: associated (psi = phi) keeps phi; psi = 0 gives tan phi* = sin phi.
    for phi in (20, 35, 50):
        assert abs(davis_angle(phi, phi) - phi) < 1e-9
        assert abs(math.tan(math.radians(davis_angle(phi, 0))) - math.sin(math.radians(phi))) < 1e-12
    assert abs(davis_angle(40, 0) - 32.7324) < 1e-3
    for phi in (5.0, 33.3, 60.5):
        assert abs(effective_angle(n_q(phi)) - phi) < 1e-9
    # Prandtl's undrained mechanism (phi = 0): B beyond the edge, the fan's radius B / sqrt(2) deep.
    reach, depth = mechanism(0.0, 0.5)
    assert abs(reach - 1.0) < 1e-12 and abs(depth - 1.0 / math.sqrt(2)) < 1e-12, (reach, depth)
    assert mechanism(40, 0.025)[0] > mechanism(30, 0.025)[0] > mechanism(0, 0.025)[0]
    print("bearing_capacity self-test: N_q(20/30/40/45) = %.2f / %.2f / %.2f / %.2f; Davis(40, 0) = %.2f deg"
          % (n_q(20), n_q(30), n_q(40), n_q(45), davis_angle(40, 0)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--phi", type=float, help="friction angle [deg]")
    ap.add_argument("--psi", type=float, default=0.0, help="dilatancy angle [deg] (Davis)")
    ap.add_argument("--q0", type=float, default=50e3, help="surcharge [Pa]")
    ap.add_argument("--effective", type=float, metavar="NQ", help="print the phi whose N_q is NQ")
    ap.add_argument("--half-width", type=float, help="with --phi: the size of Prandtl's mechanism "
                    "under a rough footing of this half-width [m]")
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.self_test:
        self_test()
    if a.phi is not None:
        d = davis_angle(a.phi, a.psi)
        print("phi %.2f deg: N_q %.2f, q_u %.4g Pa; Davis (psi %.2f deg): phi* %.2f deg, N_q %.2f, q_u %.4g Pa"
              % (a.phi, n_q(a.phi), a.q0 * n_q(a.phi), a.psi, d, n_q(d), a.q0 * n_q(d)))
        if a.half_width is not None:
            reach, depth = mechanism(a.phi, a.half_width)
            print("Prandtl's mechanism under a rough footing of half-width %g m: %.3f m beyond its edge, "
                  "%.3f m deep" % (a.half_width, reach, depth))
    if a.effective is not None:
        print("N_q %.4g: phi %.2f deg" % (a.effective, effective_angle(a.effective)))


if __name__ == "__main__":
    main()
