"""Quasi-2D granular column collapse in YADE: the pure-DEM reference of issue 16 (section 1, ref. a).

  nice -n 10 yade -j1 -n -x tools/yade_column_collapse.py --a 1 --n 2000 --out docs/data/column_collapse_yade

Set-up (docs/column_collapse_reference.md says why):
- periodic cell: y (slab thickness W, default 4 d50) is the periodic direction that matters; x and z
  are periodic too (YADE's cell is periodic in all three) but sized so that nothing reaches around;
- rough base: a square lattice (pitch d50) of fixed spheres of diameter d50 and of the grain material,
  top at z = 0, covering the whole period in x and y;
- back wall at x = 0 and gate at x = L0: square lattices (pitch d50/2) of fixed frictionless spheres of
  diameter d50/2 without rolling resistance (a nearly smooth wall); the periodic image of the back wall
  also closes the far end of the base, at x = Lx;
- grains: CohFrictMat(isCohesive=False, momentRotationLaw=True) with the parameters of
  jobs/triaxial_dem.toml ([dem.material]), Law2_ScGeom6D_CohFrictPhys_CohesionMoment(
  useIncrementalForm=True, always_use_moment_law=True): /work/shared/reference/README.md sections 1-3;
  PSD: mass fraction passing linear between 0.65 and 1.35 d50 (makeCloud, distributeMass=True);
- deposition: random cloud behind the gate, settled under gravity g_prep = prep_g * g (the rigid-grain
  limit: gravity only sets the time scale, so a larger g only shortens the deposition), then relaxed
  under g until the unbalanced force is below 0.01; H0 is then measured; the gate is removed at t = 0;
- Cundall non-viscous damping lambda (default 0.2, as in the RVEs) on the contact forces only
  (NewtonIntegrator.dampGravity=False: YADE's default would also damp gravity, i.e. slow free fall by
  lambda); the time step from GlobalStiffnessTimeStepper (safety 0.8, as in the reference README).

Outputs (small CSVs, prefix <out>/<tag>_): timeseries.csv (t, L(t), H(t), kinetic energy), profiles.csv
(h(x) at t/t* = 0, 1, 2, 3, 4, 6, 8 and at the end), summary.csv (one row). t* = sqrt(H0/g).
"""
import argparse
import csv
import math
import os
import sys
import time

from yade import O, pack, utils
from yade.wrapper import (CohFrictMat, ForceResetter, GlobalStiffnessTimeStepper, InsertionSortCollider,
                          InteractionLoop, NewtonIntegrator, Bo1_Sphere_Aabb, Ig2_Sphere_Sphere_ScGeom6D,
                          Ip2_CohFrictMat_CohFrictMat_CohFrictPhys, Law2_ScGeom6D_CohFrictPhys_CohesionMoment)

ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
ap.add_argument("--a", type=float, required=True, help="aspect ratio H0/L0 (target; measured H0 reported)")
ap.add_argument("--n", type=int, default=2000, help="number of grains in the column")
ap.add_argument("--width", type=float, default=4.0, help="slab thickness W in d50 (periodic along y)")
ap.add_argument("--damping", type=float, default=0.2, help="Cundall non-viscous damping lambda")
ap.add_argument("--prep-g", type=float, default=20.0, help="gravity factor during deposition")
ap.add_argument("--phi-guess", type=float, default=0.50, help="solid fraction assumed to size L0")
ap.add_argument("--relax-max", type=int, default=60000, help="most relaxation steps at 1 g")
ap.add_argument("--tmax", type=float, default=10.0, help="stop at this t/t* at the latest")
ap.add_argument("--max-wall", type=float, default=1e9, help="stop after this many wall seconds")
ap.add_argument("--seed", type=int, default=1)
ap.add_argument("--out", default="docs/data/column_collapse_yade")
ap.add_argument("--tag", default=None, help="file prefix (default a<a>_n<n>)")
args = ap.parse_args(sys.argv[1:])
tag = args.tag or f"a{args.a:g}_n{args.n}"
os.makedirs(args.out, exist_ok=True)
wall0 = time.time()

# --- material and geometry -------------------------------------------------------------------
G = 9.81
RHO, E, KS_KN, PHI = 2650.0, 3e8, 0.5, 30.0
ALPHA_R, ETA_R = 2.0, 0.3
D50, DMIN, DMAX = 2e-4, 1.3e-4, 2.7e-4
W = args.width * D50
# number-mean grain volume for a mass fraction passing linear in d (dn/dd ~ d^-3)
VMEAN = math.pi / 6 * (DMAX - DMIN) / ((DMIN ** -2 - DMAX ** -2) / 2)
area = args.n * VMEAN / (args.phi_guess * W)  # column area in the x-z plane
L0 = math.sqrt(area / args.a)
H0_target = args.a * L0
DW = D50 / 2  # wall lattice spheres
Lx = D50 * math.ceil((L0 * (2.0 + 1.6 * args.a) + 10 * D50) / D50)
cloud_top = 2.2 * H0_target + 4 * D50
Lz = cloud_top + 4 * D50

O.periodic = True
O.cell.setBox(Lx, W, Lz)
grain = O.materials.append(CohFrictMat(young=E, poisson=KS_KN, frictionAngle=math.radians(PHI), density=RHO,
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

newton = NewtonIntegrator(damping=args.damping, gravity=(0, 0, -args.prep_g * G), dampGravity=False)
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
      f"L0={L0:.4e} H0_target={H0_target:.4e} W={W:.3e} cell=({Lx:.3e},{W:.3e},{Lz:.3e})", flush=True)


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


prep_steps = settle(f"deposition at {args.prep_g:g} g", args.prep_g, 40000, 2000000)
newton.gravity = (0, 0, -G)
prep_steps += settle("relaxation at 1 g", 1.0, 10000, args.relax_max)

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
print(f"[{tag}] deposited: H0={H0:.4e} m, a={H0 / L0:.3f}, phi0={phi0:.3f}, t*={tstar:.4e} s, "
      f"prep steps={prep_steps}", flush=True)


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
              "L_maxgrain_m", "H_back_m", "wall_s"])
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
    lmax = max(O.bodies[i].state.pos[0] % Lx + O.bodies[i].shape.radius for i in grains)
    hback = max(top[0], top[1])
    ek = utils.kineticEnergy()
    if final:  # the last row is already written: only the final profile
        for k in range(NBIN):
            prw.writerow(["final", f"{(k + 0.5) * D50:.5e}", f"{top[k]:.5e}", f"{hv[k]:.5e}"])
        pr.flush()
        return t, L, ek
    tsw.writerow([f"{t:.6e}", f"{t / tstar:.4f}", O.iter - step0, f"{O.dt:.4e}", f"{ek:.5e}",
                  f"{ek / (mass * G * H0):.5e}", f"{L:.5e}", f"{lmax:.5e}", f"{hback:.5e}",
                  f"{time.time() - wall0:.1f}"])
    ts.flush()
    for s in snap_times:
        if s not in snaps_done and t / tstar >= s - 1e-9:
            snaps_done.add(s)
            for k in range(NBIN):
                prw.writerow([s, f"{(k + 0.5) * D50:.5e}", f"{top[k]:.5e}", f"{hv[k]:.5e}"])
    pr.flush()
    hist.append((t, L, hback, ek))
    return t, L, ek


every = max(1, int(round(0.02 * tstar / O.dt)))
record()
reason = "tmax"
while True:
    O.run(every, True)
    t, L, ek = record()
    if time.time() - wall0 > args.max_wall:
        reason = "max_wall"
        break
    if t / tstar >= args.tmax:
        break
    # at rest: kinetic energy below 1e-5 M g H0 (the column before release: ~1e-5) and the front within 0.05 d50 over the last 0.5 t*
    old = [h for h in hist if h[0] <= t - 0.5 * tstar]
    if t > 1.5 * tstar and ek < 1e-5 * mass * G * H0 and old and abs(L - old[-1][1]) < 0.05 * D50:
        reason = "rest"
        break
t, Lraw, ek = record(final=True)
# the front estimator (bins of d50, threshold d50/2) puts the front of the column at rest at L_front(0),
# within a bin of L0: the runout is measured from there
Lf = L0 + (Lraw - hist[0][1])
ts.close()
pr.close()

Hf = hist[-1][2]
# collapse duration: first time the front has covered 99 % of its final runout
runout = Lf - L0
t99 = next((h[0] for h in hist if h[1] - hist[0][1] >= 0.99 * runout), float("nan")) if runout > 0 else float("nan")
ekmax = max(h[3] for h in hist)
t_ek = next((h[0] for h in hist if h[0] > 0 and h[3] >= ekmax), 0.0)
t_ek1 = next((h[0] for h in hist if h[0] > t_ek and h[3] < 0.01 * ekmax), float("nan"))
sm_path = os.path.join(args.out, f"{tag}_summary.csv")
with open(sm_path, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["tag", "a", "N", "W_over_d50", "damping", "d50_m", "L0_m", "H0_m", "phi0", "tstar_s", "L_f_m",
                "H_f_m", "runout_over_L0", "Hf_over_L0", "Hf_over_H0", "t99_over_tstar", "t_ek1pc_over_tstar",
                "t_end_over_tstar", "end_reason", "Ek_end_over_MgH0", "prep_steps", "collapse_steps",
                "mean_dt_s", "wall_s"])
    w.writerow([tag, f"{H0 / L0:.4f}", len(grains), args.width, args.damping, D50, f"{L0:.5e}", f"{H0:.5e}",
                f"{phi0:.4f}", f"{tstar:.5e}", f"{Lf:.5e}", f"{Hf:.5e}", f"{runout / L0:.4f}", f"{Hf / L0:.4f}",
                f"{Hf / H0:.4f}", f"{t99 / tstar:.3f}", f"{t_ek1 / tstar:.3f}", f"{t / tstar:.3f}", reason,
                f"{ek / (mass * G * H0):.3e}", prep_steps, O.iter - step0, f"{t / max(O.iter - step0, 1):.4e}",
                f"{time.time() - wall0:.0f}"])
print(f"[{tag}] end ({reason}) t/t*={t / tstar:.2f}: runout (Lf-L0)/L0={runout / L0:.3f}, Hf/H0={Hf / H0:.3f}, "
      f"t99/t*={t99 / tstar:.2f}, wall={time.time() - wall0:.0f} s", flush=True)
