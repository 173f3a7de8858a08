"""YADE's drained triaxial of a periodic packing with its Hertz-Mindlin law, the reference of
docs/validation/yade_element_test.md "Hertz-Mindlin" (Law2_ScGeom_MindlinPhys_Mindlin with
includeMoment). Command:

  yade -j1 -n -x tools/mpmxdem_tools/references/yade_triax_hertz_mindlin.py \
      --packing jobs/packings/packing_N1000_e0.562.txt \
      --packing-out jobs/packings/packing_N1000_hertz_mindlin.txt \
      --out tests/data/dem/yade_triax_hertz_mindlin_N1000_I2.5e-4.csv

1. The packing (an mpmxdem packing file: CELL line, then x y z r) gets the Hertz-Mindlin material
   (FrictMat E = 3 GPa, nu = 0.25, phi = 30 deg, rho = 2650 kg/m^3;
   Ip2_FrictMat_FrictMat_MindlinPhys krot = 1e-4 N m/rad, ktwist = 0, eta = 0.3) and is brought to
   100 kPa isotropically by PeriTriaxController (Cundall damping 0.2, GlobalStiffnessTimeStepper
   0.8), then written to --packing-out (positions, radii and cell: the tangential history is not
   kept, as in every packing file).
2. From that written packing (contacts rebuilt from zero history, as mpmxdem starts), a drained
   triaxial: axial strain rate I / t_ref with t_ref = d50 sqrt(rho / p0) (d50 = 2e-4 m), the two
   lateral stresses held at 100 kPa, to --eps logarithmic axial strain. Rows every --every
   steps, the columns of tests/data/dem/yade_triax_N1000_I2.5e-4.csv.

With --bench-steps N it only times YADE: the triaxial of --packing (already consolidated, e.g.
the packing-out above) for 500 untimed and N timed steps, then prints "us/particle-step X"
(tools/mpmxdem_tools/bench/bench_contact_laws.py runs it beside bench_dem).
"""
import argparse
import math
import sys
import time

from yade import O, utils
from yade.wrapper import *  # noqa: F401,F403 (engines)

ap = argparse.ArgumentParser()
ap.add_argument("--packing", required=True)
ap.add_argument("--packing-out", default=None)
ap.add_argument("--out", default=None)
ap.add_argument("--young", type=float, default=3e9)
ap.add_argument("--poisson", type=float, default=0.25)
ap.add_argument("--krot", type=float, default=1e-4)
ap.add_argument("--eta", type=float, default=0.3)
ap.add_argument("--friction", type=float, default=30.0)
ap.add_argument("--density", type=float, default=2650.0)
ap.add_argument("--pressure", type=float, default=1e5)
ap.add_argument("--inertial", type=float, default=2.5e-4)
ap.add_argument("--eps", type=float, default=0.25)
ap.add_argument("--every", type=int, default=1000)
ap.add_argument("--bench-steps", type=int, default=0)
a = ap.parse_args(sys.argv[1:])

d50 = 2e-4
rate = a.inertial / (d50 * math.sqrt(a.density / a.pressure))


def read_packing(path):
    cell, spheres = None, []
    for line in open(path):
        t = line.split()
        if not t:
            continue
        if t[0] in ("CELL", "#") and len(t) >= 4 and (t[0] == "CELL" or t[1] == "CELL"):
            v = t[1:4] if t[0] == "CELL" else t[2:5]
            cell = [float(x) for x in v]
        elif t[0].startswith("#") or t[0] in ("HSIZE",):
            continue
        else:
            spheres.append([float(x) for x in t[:4]])
    return cell, spheres


def scene(cell, spheres):
    O.reset()
    O.periodic = True
    O.cell.hSize = Matrix3(cell[0], 0, 0, 0, cell[1], 0, 0, 0, cell[2])
    mat = O.materials.append(FrictMat(young=a.young, poisson=a.poisson, density=a.density,
                                      frictionAngle=math.radians(a.friction)))
    for x, y, z, r in spheres:
        O.bodies.append(utils.sphere((x, y, z), r, material=mat))
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom()],
                        [Ip2_FrictMat_FrictMat_MindlinPhys(krot=a.krot, ktwist=0.0, eta=a.eta)],
                        [Law2_ScGeom_MindlinPhys_Mindlin(includeMoment=True)]),
        GlobalStiffnessTimeStepper(timestepSafetyCoefficient=0.8),
        PeriTriaxController(label="triax", dynCell=True, goal=(-a.pressure,) * 3, stressMask=7,
                            maxUnbalanced=1e-4, relStressTol=1e-4, maxStrainRate=(1.0, 1.0, 1.0)),
        NewtonIntegrator(damping=0.2),
    ]


def stress():
    return utils.getStress()


def start_triaxial():
    triax.stressMask = 3
    triax.goal = (-a.pressure, -a.pressure, -1.02 * a.eps)  # YADE: logarithmic cell strain
    triax.maxStrainRate = (10.0 * rate, 10.0 * rate, rate)
    triax.maxUnbalanced = 10.0  # never "done" on balance: the run stops at --eps
    triax.doneHook = ""


if a.bench_steps > 0:
    cell, spheres = read_packing(a.packing)
    scene(cell, spheres)
    O.run(200, True)
    start_triaxial()
    O.run(500, True)
    t = time.time()
    O.run(a.bench_steps, True)
    wall = time.time() - t
    print(f"us/particle-step {1e6 * wall / (a.bench_steps * len(O.bodies)):.4f} "
          f"({a.bench_steps} steps, {len(O.bodies)} spheres, {wall:.2f} s)")
    sys.exit(0)

# 1. Isotropic consolidation with the Hertz-Mindlin law.
cell, spheres = read_packing(a.packing)
scene(cell, spheres)
t0 = time.time()
while O.iter < 400000:
    O.run(1000, True)
    s = stress()
    off = max(abs(-s[k, k] - a.pressure) for k in range(3)) / a.pressure
    if off < 1e-3 and utils.unbalancedForce() < 1e-4:
        break
s = stress()
vs = sum(4.0 / 3.0 * math.pi * b.shape.radius ** 3 for b in O.bodies)
print(f"isotropic: {O.iter} steps, p = {-s.trace() / 3:.6e} Pa, e = {O.cell.volume / vs - 1:.5f}, "
      f"unbalanced {utils.unbalancedForce():.2e}, {time.time() - t0:.0f} s", flush=True)
with open(a.packing_out, "w") as f:
    size = O.cell.size
    f.write(f"# YADE Hertz-Mindlin packing ({len(O.bodies)} spheres) consolidated to {a.pressure:g} Pa "
            f"isotropically by tools/mpmxdem_tools/references/yade_triax_hertz_mindlin.py, yade 2023.02a, iter {O.iter}\n")
    f.write(f"# E {a.young:g} nu {a.poisson:g} phi {a.friction:g} krot {a.krot:g} eta {a.eta:g} "
            f"rho {a.density:g}; e {O.cell.volume / vs - 1:.6f}; positions wrapped into the cell\n")
    f.write(f"CELL {size[0]!r} {size[1]!r} {size[2]!r}\n")
    for b in O.bodies:
        p = O.cell.wrap(b.state.pos)
        f.write(f"{p[0]!r} {p[1]!r} {p[2]!r} {b.shape.radius!r}\n")

# 2. Drained triaxial from the written packing (zero tangential history).
cell, spheres = read_packing(a.packing_out)
scene(cell, spheres)
triax.goal = (-a.pressure, -a.pressure, -a.pressure)
O.run(200, True)  # the contacts form again; the servo holds 100 kPa
lz0 = O.cell.size[2]
v0 = O.cell.volume
start_triaxial()
out = open(a.out, "w")
out.write("iter,time,dt,eps_a,eps_v,p,q,sig_a,sig_r,sxx,syy,szz,sxy,sxz,syz,e,Z,Zm,nContacts,"
          "unbalanced,wall_s\n")
t1 = time.time()
while True:
    s = stress()
    eps_a = -math.log(O.cell.size[2] / lz0)
    eps_v = -math.log(O.cell.volume / v0)
    sig_a = -s[2, 2]
    sig_r = -(s[0, 0] + s[1, 1]) / 2
    p = -s.trace() / 3
    n = sum(1 for i in O.interactions if i.isReal)
    out.write(",".join(str(x) for x in [
        O.iter, f"{O.time:.8e}", f"{O.dt:.6e}", f"{eps_a:.6e}", f"{eps_v:.6e}", f"{p:.6e}",
        f"{sig_a - sig_r:.6e}", f"{sig_a:.6e}", f"{sig_r:.6e}", f"{s[0, 0]:.6e}", f"{s[1, 1]:.6e}",
        f"{s[2, 2]:.6e}", f"{s[0, 1]:.6e}", f"{s[0, 2]:.6e}", f"{s[1, 2]:.6e}",
        f"{O.cell.volume / vs - 1:.6f}", f"{utils.avgNumInteractions():.5f}",
        f"{utils.avgNumInteractions(skipFree=True):.5f}", n, f"{utils.unbalancedForce():.4e}",
        f"{time.time() - t1:.2f}"]) + "\n")
    out.flush()
    if eps_a >= a.eps:
        break
    O.run(a.every, True)
print(f"triaxial: to eps_a {eps_a:.4f} in {O.iter} steps, {time.time() - t1:.0f} s -> {a.out}")
