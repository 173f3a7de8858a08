"""Two-sphere golden trajectory of YADE's Hertz-Mindlin law (Law2_ScGeom_MindlinPhys_Mindlin with
includeMoment, no damping, no adhesion), the data of the dem test
ContactLawHertzMindlin.YadeTwoSphereTrajectory:

  yade -j1 -n -x tools/mpmxdem_tools/references/yade_hertz_mindlin_pair.py tests/data/dem/yade_hertz_mindlin_pair.csv

The same programme as the CohFrict trajectory of docs/validation/yade_reference.md: sphere 1
(R1 = 1e-4 m) at the origin, sphere 2 (R2 = 0.7e-4 m) at x = R1 + R2 + 1e-7, both moved at
prescribed velocities (every degree of freedom blocked), dt = 1e-9 s. Phases:
  A   sphere 2 along -x at 1 m/s, 1100 steps (the gap closes, overlap 1e-6 m);
  B1  sphere 2 along +y at 1 m/s, 3000 steps (elastic, then Coulomb sliding); B2 along -y, 6000;
      B3 along +y, 3000;
  C1  pure rolling about z: w2 = +200 rad/s, w1 = -200 R2/R1 rad/s, 20000 steps (the bending
      moment reaches its cap); C2 reversed, 40000 steps;
  D   twisting about the normal: w2 = +100 rad/s, w1 = -100 rad/s about x, 20000 steps (no cap).
Rows every step in A, every 5 in B, every 20 in C and D. Columns: step, phase, x2, y2, theta1z,
theta2z, delta, Fn, Fs_y, |Fs|, Mb_z, |Mb|, |Mt|, kn, ks (YADE's phys.kn, phys.ks: the tangent
stiffnesses 3/2 kno sqrt(delta) and kso sqrt(delta)).

Material: FrictMat E = 3e8 Pa, nu = 0.25, phi = 30 deg, rho = 2650 kg/m^3; Ip2_FrictMat_FrictMat_
MindlinPhys(krot = 2e-5 N m/rad, ktwist = 1e-5 N m/rad, eta = 0.3).
"""
import math
import sys

out = sys.argv[1] if len(sys.argv) > 1 else "yade_hertz_mindlin_pair.csv"
r1, r2 = 1e-4, 0.7e-4
dt = 1e-9

O.reset()
mat = O.materials.append(FrictMat(young=3e8, poisson=0.25, frictionAngle=math.radians(30),
                                  density=2650))
b1 = O.bodies.append(sphere((0, 0, 0), r1, material=mat, fixed=True))
b2 = O.bodies.append(sphere((r1 + r2 + 1e-7, 0, 0), r2, material=mat, fixed=True))
for b in (b1, b2):
    O.bodies[b].state.blockedDOFs = "xyzXYZ"
law = Law2_ScGeom_MindlinPhys_Mindlin(includeMoment=True, preventGranularRatcheting=True,
                                      neverErase=False)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_MindlinPhys(krot=2e-5, ktwist=1e-5, eta=0.3)],
                    [law]),
    NewtonIntegrator(damping=0.0),
]
O.dt = dt

phases = [
    ("A", 1100, 1, (-1, 0, 0), (0, 0, 0), (0, 0, 0)),
    ("B1", 3000, 5, (0, 1, 0), (0, 0, 0), (0, 0, 0)),
    ("B2", 6000, 5, (0, -1, 0), (0, 0, 0), (0, 0, 0)),
    ("B3", 3000, 5, (0, 1, 0), (0, 0, 0), (0, 0, 0)),
    ("C1", 20000, 20, (0, 0, 0), (0, 0, -200.0 * r2 / r1), (0, 0, 200.0)),
    ("C2", 40000, 20, (0, 0, 0), (0, 0, 200.0 * r2 / r1), (0, 0, -200.0)),
    ("D", 20000, 20, (0, 0, 0), (-100.0, 0, 0), (100.0, 0, 0)),
]

theta1 = theta2 = 0.0
rows = []
step = 0
for name, n, every, v2, w1, w2 in phases:
    O.bodies[b1].state.vel = Vector3(0, 0, 0)
    O.bodies[b2].state.vel = Vector3(*v2)
    O.bodies[b1].state.angVel = Vector3(*w1)
    O.bodies[b2].state.angVel = Vector3(*w2)
    for _ in range(n):
        O.step()
        step += 1
        theta1 += w1[2] * dt
        theta2 += w2[2] * dt
        if step % every:
            continue
        p1, p2 = O.bodies[b1].state.pos, O.bodies[b2].state.pos
        i = O.interactions[b1, b2] if O.interactions.has(b1, b2) else None
        if i is None or not i.isReal:
            vals = [0.0] * 9
        else:
            g, ph = i.geom, i.phys
            fs = ph.shearForce
            vals = [g.penetrationDepth, ph.normalForce.norm(), fs[1], fs.norm(),
                    ph.momentBend[2], ph.momentBend.norm(), ph.momentTwist.norm(), ph.kn, ph.ks]
        rows.append([step, name, p2[0] - p1[0], p2[1] - p1[1], theta1, theta2] + vals)

with open(out, "w") as f:
    f.write("step,phase,x2,y2,theta1z,theta2z,delta,Fn,Fs_y,Fs_norm,Mb_z,Mb_norm,Mt_norm,kn,ks\n")
    for r in rows:
        f.write(",".join([str(r[0]), r[1]] + [repr(float(x)) for x in r[2:]]) + "\n")
print(f"yade_hertz_mindlin_pair: {len(rows)} rows, last step {step} -> {out}")
