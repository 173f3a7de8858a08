"""Quasi-2D granular column collapse in YADE: the pure-DEM reference of the column collapse
(docs/validation/column_collapse_reference.md), dense and run to rest.

Dense reference (the defaults):
  nice -n 5 yade -j1 -n -x tools/mpmxdem_tools/references/yade_column_collapse.py --a 2 --l0 14.4 --width 5 --phi-guess 0.585 \
      --damping 0.05 --out docs/data/column_collapse_yade --tag dense_a2_n3000_l0.05
  (3,009 grains, L0 = 14.4 d50, slab W = 5 d50; docs/data/column_collapse_yade/README_dense.md lists the runs)
Loose, heavily damped series (the files a*_n1000_*, a1_n2000_* were made so):
  nice -n 10 yade -j1 -n -x tools/mpmxdem_tools/references/yade_column_collapse.py --a 1 --n 2000 --legacy --out docs/data/column_collapse_yade
  (--legacy = --width 4 --damping 0.2 --prep-damping 0.2 --prep-friction 30 --phi-guess 0.50 --rest legacy --tmax 10)

Set-up (docs/validation/column_collapse_reference.md says why):
- periodic cell: y (slab thickness W, default 5 d50) is the periodic direction that matters; x and z
  are periodic too (YADE's cell is periodic in all three) but sized so that nothing reaches around;
- rough base: a square lattice (pitch d50) of fixed spheres of diameter d50 and of the grain material,
  top at z = 0, covering the whole period in x and y;
- back wall at x = 0 and gate at x = L0: square lattices (pitch d50/2) of fixed frictionless spheres of
  diameter d50/2 without rolling resistance (a nearly smooth wall); the periodic image of the back wall
  also closes the far end of the base, at x = Lx;
- grains: CohFrictMat(isCohesive=False, momentRotationLaw=True) with the parameters of
  jobs/triaxial_dem.toml ([dem.material]), Law2_ScGeom6D_CohFrictPhys_CohesionMoment(
  useIncrementalForm=True, always_use_moment_law=True): shared/reference/README.md beside the checkout sections 1-3;
  PSD: mass fraction passing linear between 0.65 and 1.35 d50 (makeCloud, distributeMass=True);
- column size: either --n grains (L0 from --phi-guess) or --l0 L0/d50 (N from --phi-guess); H0 = a L0
  is then what the deposit gives (the measured a is reported);
- deposition: random cloud behind the gate, settled under gravity g_prep = prep_g * g (the rigid-grain
  limit: gravity only sets the time scale, so a larger g only shortens the deposition) with the contact
  friction lowered to --prep-friction (default 1 deg, as the RVEs are prepared: [dem.preparation]
  friction_angle of jobs/column_collapse_a2.toml) and Cundall damping --prep-damping (default 0.2);
  then the friction is restored to 30 deg (material and every existing contact) and the column
  relaxed under g; H0 and the solid fraction are then measured; the gate is removed at t = 0;
- Cundall non-viscous damping lambda (--damping, default 0.05) on the contact forces only
  (NewtonIntegrator.dampGravity=False: YADE's default would also damp gravity, i.e. slow free fall by
  lambda); the time step from GlobalStiffnessTimeStepper (safety 0.8, as in the reference README).
- end: at rest (--rest): "ek": kinetic energy (translation + rotation) below --rest-ek (1e-6) times the
  potential energy released since t = 0; "geom": both fronts and the back height unchanged over the
  last --rest-window t* (1): the mean of each over the second half of the window within --rest-tol d50
  (0.5) of its mean over the first half (the fronts of a thin tail jump by a few d50 from bin to bin, so
  a max-min test never ends), and Ek below --rest-geom-ek (1e-2) times the energy released (without
  it, the a = 2, L0 = 7.2 d50 run stopped at 3.8 t* with grains still rolling out); "both" (default):
  the first of the two;
  "legacy": Ek < 1e-5 M g H0 and front within 0.05 d50 over 0.5 t*. --tmax (t/t*) and
  --max-wall are safeties only; every output is flushed as the run goes and the summary row is
  rewritten (end_reason "running") every 0.5 t*, so a stopped run is usable.

Fronts (all three in the time series; runouts and fronts at 1, 2, 3 t* of the first two in the summary):
- L_front: rightmost x where the equivalent height (solid volume of the d50-wide bin / (d50 W phi0))
  is >= d50/2 (the original reference's definition; a detached cluster of a few grains can carry it);
- L_cont: continuous deposit front: walking from the back wall, the first x where the equivalent height
  falls below one d50 (interpolated within the bin);
- L_maxgrain: the farthest grain (x + r), noisy.
Runouts are (L(t) - L(0)) / L0 of each front estimator (measured from its own value on the column at
rest, within a bin of L0).

Outputs (small CSVs, prefix <out>/<tag>_): timeseries.csv (t, L(t), H(t), kinetic energy), profiles.csv
(h(x) at t/t* = 0, 1, 2, 3, 4, 6, 8 and at the end), summary.csv (one row). t* = sqrt(H0/g).
"""
import argparse
import csv
import math
import os
import signal
import sys
import time

from yade import O, pack, utils
from yade.wrapper import (CohFrictMat, ForceResetter, GlobalStiffnessTimeStepper, InsertionSortCollider,
                          InteractionLoop, NewtonIntegrator, Bo1_Sphere_Aabb, Ig2_Sphere_Sphere_ScGeom6D,
                          Ip2_CohFrictMat_CohFrictMat_CohFrictPhys, Law2_ScGeom6D_CohFrictPhys_CohesionMoment)

ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
ap.add_argument("--a", type=float, required=True, help="aspect ratio H0/L0 (target; measured H0 reported)")
ap.add_argument("--n", type=int, default=None, help="number of grains in the column (L0 from --phi-guess)")
ap.add_argument("--l0", type=float, default=None, help="column length L0 in d50 (N from --phi-guess)")
ap.add_argument("--width", type=float, default=5.0, help="slab thickness W in d50 (periodic along y)")
ap.add_argument("--damping", type=float, default=0.05, help="Cundall non-viscous damping lambda of the collapse")
ap.add_argument("--prep-damping", type=float, default=0.2, help="Cundall damping during deposition and relaxation")
ap.add_argument("--prep-friction", type=float, default=1.0, help="contact friction angle (deg) during deposition")
ap.add_argument("--prep-g", type=float, default=20.0, help="gravity factor during deposition")
ap.add_argument("--phi-guess", type=float, default=0.60, help="solid fraction assumed to size L0 or N")
ap.add_argument("--relax-max", type=int, default=60000, help="most relaxation steps at 1 g")
ap.add_argument("--rest", choices=["both", "ek", "geom", "legacy"], default="both", help="at-rest criterion")
ap.add_argument("--rest-ek", type=float, default=1e-6, help="'ek': Ek below this times the energy released")
ap.add_argument("--rest-window", type=float, default=1.0, help="'geom': window in t*")
ap.add_argument("--rest-tol", type=float, default=0.5,
                help="'geom': largest change of the mean over the window's two halves, in d50")
ap.add_argument("--rest-geom-ek", type=float, default=1e-2,
                help="'geom' also needs Ek below this times the energy released (inf: no such guard)")
ap.add_argument("--tmax", type=float, default=None, help="stop at this t/t* at the latest (safety; 20, legacy 10)")
ap.add_argument("--max-wall", type=float, default=1e9, help="stop after this many wall seconds (safety)")
ap.add_argument("--legacy", action="store_true", help="the original loose, damped set-up (see the header)")
ap.add_argument("--young", type=float, default=3e8,
                help="contact Young's modulus E [Pa] (the RVEs' 300 MPa; smaller: a softer contact, "
                     "for the stiffness-number study of docs/validation/column_collapse.md)")
ap.add_argument("--seed", type=int, default=1)
ap.add_argument("--out", default="docs/data/column_collapse_yade")
ap.add_argument("--tag", default=None, help="file prefix (default a<a>_n<n>)")
args = ap.parse_args(sys.argv[1:])
if args.legacy:
    args.width, args.damping, args.prep_damping, args.prep_friction = 4.0, 0.2, 0.2, 30.0
    args.phi_guess, args.rest = 0.50, "legacy"
if args.tmax is None:
    args.tmax = 10.0 if args.legacy else 20.0
if (args.n is None) == (args.l0 is None):
    sys.exit("give exactly one of --n and --l0")
os.makedirs(args.out, exist_ok=True)
wall0 = time.time()

# --- material and geometry -------------------------------------------------------------------
G = 9.81
RHO, E, KS_KN, PHI = 2650.0, args.young, 0.5, 30.0
ALPHA_R, ETA_R = 2.0, 0.3
D50, DMIN, DMAX = 2e-4, 1.3e-4, 2.7e-4
W = args.width * D50
# number-mean grain volume for a mass fraction passing linear in d (dn/dd ~ d^-3)
VMEAN = math.pi / 6 * (DMAX - DMIN) / ((DMIN ** -2 - DMAX ** -2) / 2)
if args.n is None:
    L0 = args.l0 * D50
    args.n = int(round(args.phi_guess * W * args.a * L0 * L0 / VMEAN))
else:
    area = args.n * VMEAN / (args.phi_guess * W)  # column area in the x-z plane
    L0 = math.sqrt(area / args.a)
H0_target = args.a * L0
DW = D50 / 2  # wall lattice spheres
tag = args.tag or f"a{args.a:g}_n{args.n}"
Lx = D50 * math.ceil((L0 * (2.0 + 1.6 * args.a) + 10 * D50) / D50)
cloud_top = 2.2 * H0_target + 4 * D50
Lz = cloud_top + 4 * D50

O.periodic = True
O.cell.setBox(Lx, W, Lz)
grain = O.materials.append(CohFrictMat(young=E, poisson=KS_KN, frictionAngle=math.radians(args.prep_friction),
                                       density=RHO,
                                       isCohesive=False, momentRotationLaw=True, alphaKr=ALPHA_R, etaRoll=ETA_R,
                                       alphaKtw=0.0, etaTwist=-1.0, label="grain"))
smooth = O.materials.append(CohFrictMat(young=E, poisson=KS_KN, frictionAngle=0.0, density=RHO, isCohesive=False,
                                        momentRotationLaw=False, alphaKr=0.0, etaRoll=-1.0, label="smooth"))


FIXED_MASK = 3  # bit 2 set on fixed spheres only: the collider skips fixed-fixed pairs


def lattice_wall(x_centre, height):
    ids = []
    for j in range(int(round(W / DW))):
        for k in range(int(math.ceil(height / DW))):
            ids.append(O.bodies.append(utils.sphere((x_centre, (j + 0.5) * DW, (k + 0.5) * DW), DW / 2, fixed=True,
                                                    material=smooth, mask=FIXED_MASK)))
    return ids


base = [O.bodies.append(utils.sphere(((i + 0.5) * D50, (j + 0.5) * D50, -D50 / 2), D50 / 2, fixed=True,
                                     material=grain, mask=FIXED_MASK))
        for i in range(int(round(Lx / D50))) for j in range(int(round(W / D50)))]
back = lattice_wall(-DW / 2, cloud_top + D50)
gate = lattice_wall(L0 + DW / 2, cloud_top + D50)

sp = pack.SpherePack()
made = sp.makeCloud((0, 0, 0), (L0, W, cloud_top), num=args.n, psdSizes=[DMIN, DMAX], psdCumm=[0.0, 1.0],
                    distributeMass=True, seed=args.seed)
if made != args.n:
    sys.exit(f"makeCloud placed {made} of {args.n} grains: raise cloud_top")
grains = [O.bodies.append(utils.sphere(c, r, material=grain)) for c, r in sp]
rmin = min(O.bodies[i].shape.radius for i in grains)
rmax = max(O.bodies[i].shape.radius for i in grains)

newton = NewtonIntegrator(damping=args.prep_damping, gravity=(0, 0, -args.prep_g * G), dampGravity=False)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()], avoidSelfInteractionMask=2),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom6D()], [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys()],
                    [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(useIncrementalForm=True, always_use_moment_law=True)]),
    GlobalStiffnessTimeStepper(timestepSafetyCoefficient=0.8, timeStepUpdateInterval=100,
                               defaultDt=0.4 * rmin / math.sqrt(E / RHO)),
    newton,
]
O.dt = 0.4 * rmin / math.sqrt(E / RHO)
print(f"[{tag}] N={len(grains)} (radii {rmin:.3e}-{rmax:.3e}) base={len(base)} walls={len(back)}+{len(gate)} "
      f"L0={L0:.4e} (L0/d50={L0 / D50:.2f}) H0_target={H0_target:.4e} W={W:.3e} (W/d50={args.width:g}) "
      f"cell=({Lx:.3e},{W:.3e},{Lz:.3e}); prep friction {args.prep_friction:g} deg, prep damping "
      f"{args.prep_damping:g}, damping {args.damping:g}, rest criterion {args.rest}", flush=True)


def settle(label, gfac, min_steps, max_steps, tol=1e-5):
    """Runs until the kinetic energy is below tol * M g H0 (YADE's unbalancedForce does not see the gravity
    that NewtonIntegrator adds, so it stays ~ m g / mean contact force ~ 0.04 here at rest)."""
    ek_ref = tol * sum(O.bodies[i].state.mass for i in grains) * gfac * G * H0_target
    done = 0
    while done < max_steps:
        O.run(2000, True)
        done += 2000
        if done % 20000 == 0:
            print(f"[{tag}]   {label}: {done} steps, t={O.time:.3e}, unbalanced={utils.unbalancedForce():.3e}, "
                  f"Ek={utils.kineticEnergy():.3e}, dt={O.dt:.3e}, wall={time.time() - wall0:.0f} s", flush=True)
        if done >= min_steps and utils.kineticEnergy() < ek_ref:
            break
    print(f"[{tag}] {label}: {done} steps, t={O.time:.4e} s, unbalanced={utils.unbalancedForce():.3e}, "
          f"dt={O.dt:.3e}, wall={time.time() - wall0:.0f} s", flush=True)
    return done


prep_steps = settle(f"deposition at {args.prep_g:g} g, friction {args.prep_friction:g} deg", args.prep_g, 40000,
                    2000000)
if args.prep_friction != PHI:  # restore the friction: material (new contacts) and every existing contact
    O.materials[grain].frictionAngle = math.radians(PHI)
    nfix = 0
    for it in O.interactions:
        if it.isReal:
            ph = min(O.bodies[it.id1].material.frictionAngle, O.bodies[it.id2].material.frictionAngle)
            it.phys.tangensOfFrictionAngle = math.tan(ph)
            nfix += 1
    print(f"[{tag}] friction restored to {PHI:g} deg on the material and {nfix} contacts", flush=True)
newton.gravity = (0, 0, -G)
prep_steps += settle("relaxation at 1 g", 1.0, 10000, args.relax_max)
wall_prep = time.time() - wall0
newton.damping = args.damping

# --- measures ---------------------------------------------------------------------------------
NBIN = int(Lx / D50)


def columns():
    """Per x-bin of width d50: top height max(z+r) and solid volume."""
    top = [0.0] * NBIN
    vol = [0.0] * NBIN
    for i in grains:
        b = O.bodies[i]
        x = b.state.pos[0] % Lx  # wrapped (the back wall's image closes the period)
        k = min(int(x / D50), NBIN - 1)
        r = b.shape.radius
        top[k] = max(top[k], b.state.pos[2] + r)
        vol[k] += 4.0 / 3.0 * math.pi * r ** 3
    return top, vol


top0, vol0 = columns()
nL0 = max(1, int(L0 / D50))
inner = sorted(top0[1:nL0 - 1]) if nL0 > 3 else top0[:nL0]
H0 = inner[len(inner) // 2]  # median top height behind the gate
vsolid = sum(vol0)
phi0 = vsolid / (L0 * W * H0)
tstar = math.sqrt(H0 / G)
mass = sum(O.bodies[i].state.mass for i in grains)
# core solid fraction: grains whose centre lies at least 2 d50 from the walls and the base and 3 d50 below the top
cx0, cx1, cz0, cz1 = 2 * D50, L0 - 2 * D50, 2 * D50, H0 - 3 * D50
vcore = sum(4.0 / 3.0 * math.pi * O.bodies[i].shape.radius ** 3 for i in grains
            if cx0 <= O.bodies[i].state.pos[0] <= cx1 and cz0 <= O.bodies[i].state.pos[2] <= cz1)
phi_core = vcore / max((cx1 - cx0) * W * (cz1 - cz0), 1e-30)
z0 = {i: O.bodies[i].state.pos[2] for i in grains}
print(f"[{tag}] deposited: H0={H0:.4e} m, a={H0 / L0:.3f}, phi0={phi0:.3f}, t*={tstar:.4e} s, "
      f"prep steps={prep_steps}", flush=True)
print(f"[{tag}] core solid fraction {phi_core:.4f}, N={len(grains)}, L0/d50={L0 / D50:.2f}, H0/d50={H0 / D50:.2f}, "
      f"prep wall={wall_prep:.0f} s", flush=True)


def heights(top, vol):
    hv = [v / (D50 * W * phi0) for v in vol]  # equivalent height at the initial solid fraction
    return top, hv


def front(hv):
    """Rightmost x where the equivalent height >= d50/2 (about half a layer across the slab)."""
    thr = 0.5 * D50
    for k in range(NBIN - 1, -1, -1):
        if hv[k] >= thr:
            nxt = hv[k + 1] if k + 1 < NBIN else 0.0
            return (k + 0.5) * D50 + D50 * (hv[k] - thr) / max(hv[k] - nxt, 1e-30)
    return 0.0


def front_cont(hv):
    """Continuous deposit front: from the back wall, the first x where the equivalent height falls below d50."""
    thr = D50
    k = 0
    while k < NBIN and hv[k] >= thr:
        k += 1
    if k == 0:
        return 0.0
    nxt = hv[k] if k < NBIN else 0.0
    return (k - 0.5) * D50 + D50 * (hv[k - 1] - thr) / max(hv[k - 1] - nxt, 1e-30)


def released():
    """Potential energy released since t = 0 (J)."""
    return sum(O.bodies[i].state.mass * G * (z0[i] - O.bodies[i].state.pos[2]) for i in grains)


# Release: the gate's spheres lose their contacts and are moved next to the far end of the base (against the
# periodic image of the back wall, x = Lx, far beyond any runout); a fresh collider then sorts the bounds anew.
# Two other ways failed with YADE 2023.02a in this periodic cell: erasing the bodies (O.bodies.erase) left two
# of three N = 2000 runs stuck in InsertionSortCollider::insertionSortPeri right after the release, and
# setting their mask to 0 left the gate in place (the columns did not move).
for i in gate:
    for it in O.interactions.withBodyAll(i):  # real and potential contacts
        O.interactions.erase(it.id1, it.id2)
    p = O.bodies[i].state.pos
    O.bodies[i].state.pos = (Lx - 1.5 * DW, p[1], p[2])
O.engines = [O.engines[0], InsertionSortCollider([Bo1_Sphere_Aabb()], avoidSelfInteractionMask=2)] + O.engines[2:]
t0, step0 = O.time, O.iter
ts_path = os.path.join(args.out, f"{tag}_timeseries.csv")
pr_path = os.path.join(args.out, f"{tag}_profiles.csv")
ts = open(ts_path, "w", newline="")
tsw = csv.writer(ts)
tsw.writerow(["t_s", "t_over_tstar", "step", "dt_s", "kinetic_J", "kinetic_over_MgH0", "L_front_m",
              "L_maxgrain_m", "H_back_m", "wall_s", "L_cont_m", "released_J", "kinetic_over_released"])
pr = open(pr_path, "w", newline="")
prw = csv.writer(pr)
prw.writerow(["t_over_tstar", "x_m", "h_top_m", "h_vol_m"])
snap_times = [0, 1, 2, 3, 4, 6, 8]
snaps_done = set()
hist = []


def record(final=False):
    t = O.time - t0
    top, vol = columns()
    _, hv = heights(top, vol)
    L = front(hv)
    Lc = front_cont(hv)
    lmax = max(O.bodies[i].state.pos[0] % Lx + O.bodies[i].shape.radius for i in grains)
    hback = max(top[0], top[1])
    ek = utils.kineticEnergy()
    rel = released()
    if final:  # the last row is already written: only the final profile
        for k in range(NBIN):
            prw.writerow(["final", f"{(k + 0.5) * D50:.5e}", f"{top[k]:.5e}", f"{hv[k]:.5e}"])
        pr.flush()
        return t, L, ek
    tsw.writerow([f"{t:.6e}", f"{t / tstar:.4f}", O.iter - step0, f"{O.dt:.4e}", f"{ek:.5e}",
                  f"{ek / (mass * G * H0):.5e}", f"{L:.5e}", f"{lmax:.5e}", f"{hback:.5e}",
                  f"{time.time() - wall0:.1f}", f"{Lc:.5e}", f"{rel:.5e}", f"{ek / rel:.4e}" if rel > 0 else "nan"])
    ts.flush()
    for s in snap_times:
        if s not in snaps_done and t / tstar >= s - 1e-9:
            snaps_done.add(s)
            for k in range(NBIN):
                prw.writerow([s, f"{(k + 0.5) * D50:.5e}", f"{top[k]:.5e}", f"{hv[k]:.5e}"])
    pr.flush()
    hist.append((t, L, hback, ek, Lc, rel, lmax))
    return t, L, ek


stop_signal = []
signal.signal(signal.SIGTERM, lambda *_: stop_signal.append("sigterm"))
signal.signal(signal.SIGINT, lambda *_: stop_signal.append("sigint"))


def at(hcol, tt):
    """Value of hist column hcol at time tt (linear interpolation), nan if not reached."""
    for a_, b_ in zip(hist, hist[1:]):
        if a_[0] <= tt <= b_[0]:
            f = (tt - a_[0]) / max(b_[0] - a_[0], 1e-300)
            return a_[hcol] + f * (b_[hcol] - a_[hcol])
    return float("nan")


def write_summary(reason, t, ek):
    h0, hl = hist[0], hist[-1]
    Lf = L0 + (hl[1] - h0[1])
    runout = Lf - L0
    runout_c = hl[4] - h0[4]
    Hf = hl[2]
    t99 = next((h[0] for h in hist if h[1] - h0[1] >= 0.99 * runout), float("nan")) if runout > 0 else float("nan")
    t99c = next((h[0] for h in hist if h[4] - h0[4] >= 0.99 * runout_c), float("nan")) \
        if runout_c > 0 else float("nan")
    ekmax = max(h[3] for h in hist)
    t_ek = next((h[0] for h in hist if h[0] > 0 and h[3] >= ekmax), 0.0)
    t_ek1 = next((h[0] for h in hist if h[0] > t_ek and h[3] < 0.01 * ekmax), float("nan"))
    steps = O.iter - step0
    wall_c = time.time() - wall0 - wall_prep
    fr = {}
    for k in (1, 2, 3):
        fr[k] = ((at(1, k * tstar) - h0[1]) / L0, (at(4, k * tstar) - h0[4]) / L0)
    cols = [("tag", tag), ("a", f"{H0 / L0:.4f}"), ("N", len(grains)), ("W_over_d50", args.width),
            ("damping", args.damping), ("d50_m", D50), ("L0_m", f"{L0:.5e}"), ("H0_m", f"{H0:.5e}"),
            ("phi0", f"{phi0:.4f}"), ("tstar_s", f"{tstar:.5e}"), ("L_f_m", f"{Lf:.5e}"), ("H_f_m", f"{Hf:.5e}"),
            ("runout_over_L0", f"{runout / L0:.4f}"), ("Hf_over_L0", f"{Hf / L0:.4f}"),
            ("Hf_over_H0", f"{Hf / H0:.4f}"), ("t99_over_tstar", f"{t99 / tstar:.3f}"),
            ("t_ek1pc_over_tstar", f"{t_ek1 / tstar:.3f}"), ("t_end_over_tstar", f"{t / tstar:.3f}"),
            ("end_reason", reason), ("Ek_end_over_MgH0", f"{ek / (mass * G * H0):.3e}"),
            ("prep_steps", prep_steps), ("collapse_steps", steps), ("mean_dt_s", f"{t / max(steps, 1):.4e}"),
            ("wall_s", f"{time.time() - wall0:.0f}"),
            # the dense reference's additions
            ("L0_over_d50", f"{L0 / D50:.3f}"), ("H0_over_d50", f"{H0 / D50:.3f}"), ("phi_core", f"{phi_core:.4f}"),
            ("prep_friction_deg", args.prep_friction), ("prep_damping", args.prep_damping),
            ("rest_criterion", args.rest), ("runout_cont_over_L0", f"{runout_c / L0:.4f}"),
            ("runout_maxgrain_over_L0", f"{(hl[6] - h0[6]) / L0:.4f}"),
            ("front1_over_L0", f"{fr[1][0]:.4f}"), ("front2_over_L0", f"{fr[2][0]:.4f}"),
            ("front3_over_L0", f"{fr[3][0]:.4f}"), ("front1_cont_over_L0", f"{fr[1][1]:.4f}"),
            ("front2_cont_over_L0", f"{fr[2][1]:.4f}"), ("front3_cont_over_L0", f"{fr[3][1]:.4f}"),
            ("t99_cont_over_tstar", f"{t99c / tstar:.3f}"), ("Hback0_over_H0", f"{h0[2] / H0:.4f}"),
            ("Hf_over_Hback0", f"{Hf / h0[2]:.4f}"), ("Ek_end_over_released", f"{ek / max(hl[5], 1e-300):.3e}"),
            ("released_over_MgH0", f"{hl[5] / (mass * G * H0):.4e}"), ("wall_prep_s", f"{wall_prep:.0f}"),
            ("wall_collapse_s", f"{wall_c:.0f}"),
            ("us_per_grain_step", f"{1e6 * wall_c / max(steps * len(grains), 1):.4f}"),
            ("front_definition", "L_front: rightmost bin with equivalent height >= d50/2; cont: first bin from the "
                                 "back wall below d50; fronts k t* = (L(k t*) - L(0))/L0")]
    with open(os.path.join(args.out, f"{tag}_summary.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow([c[0] for c in cols])
        w.writerow([c[1] for c in cols])
    return runout, runout_c, Hf, t99


every = max(1, int(round(0.02 * tstar / O.dt)))
record()
reason = "tmax"
next_summary = 0.5
wall_c0 = time.time()
while True:
    O.run(every, True)
    t, L, ek = record()
    if stop_signal:
        reason = stop_signal[0]
        break
    if time.time() - wall0 > args.max_wall:
        reason = "max_wall"
        break
    if t / tstar >= args.tmax:
        break
    if t / tstar >= next_summary:
        write_summary("running", t, ek)
        h = hist[-1]
        steps = O.iter - step0
        print(f"[{tag}] t/t*={t / tstar:.2f} steps={steps} L_front-L(0)={(h[1] - hist[0][1]) / L0:.3f} L0, "
              f"L_cont-L(0)={(h[4] - hist[0][4]) / L0:.3f} L0, H_back/H0={h[2] / H0:.3f}, "
              f"Ek/MgH0={ek / (mass * G * H0):.3e}, Ek/released={ek / max(h[5], 1e-300):.3e}, "
              f"{1e6 * (time.time() - wall_c0) / max(steps * len(grains), 1):.3f} us/grain-step, "
              f"wall={time.time() - wall0:.0f} s", flush=True)
        next_summary += 0.5
    if args.rest == "legacy":
        # at rest: kinetic energy below 1e-5 M g H0 (the column before release: ~1e-5) and the front within 0.05 d50
        # over the last 0.5 t*
        old = [h for h in hist if h[0] <= t - 0.5 * tstar]
        if t > 1.5 * tstar and ek < 1e-5 * mass * G * H0 and old and abs(L - old[-1][1]) < 0.05 * D50:
            reason = "rest"
            break
        continue
    if t < 1.5 * tstar:
        continue
    if args.rest in ("both", "ek") and ek < args.rest_ek * hist[-1][5]:
        reason = f"rest_ek(Ek<{args.rest_ek:g}*released)"
        break
    if args.rest in ("both", "geom") and t >= args.rest_window * tstar and ek < args.rest_geom_ek * hist[-1][5]:
        # the front estimators jump by several d50 on a thin tail (a grain crossing a bin edge moves the bin's
        # equivalent height by ~0.13 d50 at W = 5 d50): compare the means over the two halves of the window
        h1 = [h for h in hist if t - args.rest_window * tstar <= h[0] < t - 0.5 * args.rest_window * tstar]
        h2 = [h for h in hist if h[0] >= t - 0.5 * args.rest_window * tstar]
        if h1 and h2 and all(abs(sum(h[c] for h in h2) / len(h2) - sum(h[c] for h in h1) / len(h1))
                             <= args.rest_tol * D50 for c in (1, 2, 4)):
            reason = f"rest_geom(mean fronts,H drift<{args.rest_tol:g}d50 over {args.rest_window:g}t*)"
            break
t, Lraw, ek = record(final=True)
ts.close()
pr.close()
runout, runout_c, Hf, t99 = write_summary(reason, t, ek)
print(f"[{tag}] end ({reason}) t/t*={t / tstar:.2f}: runout (Lf-L0)/L0={runout / L0:.3f} "
      f"(continuous deposit {runout_c / L0:.3f}), Hf/H0={Hf / H0:.3f}, t99/t*={t99 / tstar:.2f}, "
      f"steps={O.iter - step0}, wall={time.time() - wall0:.0f} s", flush=True)
