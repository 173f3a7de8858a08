#!/usr/bin/python3
"""Write a plane-strain strip-footing job (a boundary-value problem whose far field
idles). jobs/footing_plane_strain.toml was written by this script with its defaults; a user
changes the layer, the mesh, the footing or the RVE size here, or edits the written job.

Half of the problem (symmetry plane x = 0): a layer `width` x `depth` of granular material on
square cells of `cell`, [2, 1, 2] points per cell (one RVE each), a rigid rough footing of
half-width `half_width` (the node columns x = 0 ... half_width of the top surface, and the plane
above them) pushed down at `speed` to `settlement`. No gravity: a surcharge `pressure` on the
surface (under the footing too) and an isotropic initial state at that pressure, i.e. one DEM
preparation for every RVE; rollers on the sides (x = 0: symmetry, x = width: far field), a rough
rigid base. Mass scaling 1e4 (quasi-static). Reference quantity: the footing's reaction
(reactions.csv, footing_rz_N) against its settlement (footing_uz_m).

The footing holds the node plane of the surface for the whole run: the top row of points (a
quarter cell under the surface) must stay in the cells under it, so the settlement is at most
half a cell (checked; a deeper settlement needs a staircase of held planes as the biaxial's
platen, tools/biaxial_make_jobs.py).

    /usr/bin/python3 tools/footing_make_job.py --out jobs/footing_plane_strain.toml
    /usr/bin/python3 tools/footing_make_job.py --width 0.4 --depth 0.2 --out /tmp/footing_wide.toml
    /usr/bin/python3 tools/footing_make_job.py --check jobs/footing_plane_strain.toml  # (ctest)
"""
import argparse
import sys

DEFAULTS = dict(width=0.2, depth=0.1, cell=0.0125, half_width=0.025, settlement=0.005,
                speed=0.001, spheres=100, pressure=50e3, every=10, damping=0.2)


def fmt(x):
    """A length as it reads best in a job (no float noise): 0.0125, not 0.012500000000000001."""
    return repr(round(x, 12))


def job_text(width, depth, cell, half_width, settlement, speed, spheres, pressure, every, damping):
    nx, nz = round(width / cell), round(depth / cell)
    if abs(nx * cell - width) > 1e-9 * width or abs(nz * cell - depth) > 1e-9 * depth:
        raise ValueError("width and depth must be whole numbers of cells")
    if abs(round(half_width / cell) * cell - half_width) > 1e-9 or half_width < cell:
        raise ValueError("half_width must be a whole number (>= 1) of cells")
    if settlement > 0.5 * cell + 1e-12:
        raise ValueError("settlement %g m is more than half a cell (%g m): the top row of points "
                         "would leave the cells under the held surface" % (settlement, cell))
    rves = nx * nz * 4
    t_end = settlement / speed
    x0, z0 = -cell, -cell                     # one empty cell left of x = 0 and under the base
    xt, zt = width + cell, depth + 2 * cell   # one beyond the far side, two above the surface
    B_mm = 2e3 * half_width
    return f'''# Plane-strain strip footing on a granular layer (a scene whose far field idles).
# Written by tools/footing_make_job.py --width {width:g} --depth {depth:g} --cell {cell:g} --half-width {half_width:g}
#   --settlement {settlement:g} --speed {speed:g} --spheres {spheres} --pressure {pressure:g} --every {every}
#   --damping {damping:g}
# Half of the problem (symmetry plane x = 0): a layer {width * 1e3:g} mm wide and {depth * 1e3:g} mm deep on
# {nx} x {nz} cells of [2, 1, 2] points ({rves} RVEs of {spheres} spheres), a rigid rough footing of
# half-width {half_width * 1e3:g} mm (B = {B_mm:g} mm: the node columns x = 0 ... {half_width * 1e3:g} mm of the surface)
# pushed down at {speed * 1e3:g} mm/s to a settlement of {settlement * 1e3:g} mm ({settlement / (2 * half_width):g} B). No gravity: a
# {pressure / 1e3:g} kPa surcharge on the surface and an isotropic initial state at {pressure / 1e3:g} kPa (one
# DEM preparation for every RVE); rollers on the sides (x = 0: symmetry; x = {width * 1e3:g} mm: far field),
# a rough rigid base. Mass scaling 1e4 (quasi-static: the log reports E_kin/W_int).
# Reference quantity: the footing's reaction (reactions.csv footing_rz_N) against its settlement
# (footing_uz_m); its bearing pressure is -footing_rz_N / (half-width x thickness {cell * 1e3:g} mm)
# (tools/footing_curves.py). The default layer (200 x 100 mm, 2 B deep on a rough base) is small:
# at 0.1 B it carries 6.7 MPa against 4.8 and 4.4 on layers 2 and 3 times as wide and deep; study
# the footing itself on the larger ones (--width 0.6 --depth 0.3: 4608 RVEs, about 4 min on 2 cores).
# Sparing the idle far field: docs/validation/speed.md "Sparing on a strip footing".
#
# Run:        mpirun -n 2 --bind-to none mpmxdem run jobs/footing_plane_strain.toml --out results/footing
# Validate:   mpmxdem check jobs/footing_plane_strain.toml
title = "Plane-strain strip footing, MPM x DEM, {nx} x {nz} cells, {rves} RVEs of {spheres} spheres"

[dem.material]                 # the reference material (docs/validation/triaxial.md)
density = "2650 kg/m^3"
young_modulus = "300 MPa"
stiffness_ratio = 0.5
friction_angle = "30 deg"
rolling_stiffness = 2.0
rolling_strength = 0.3

[dem.sample]
spheres = {spheres}
psd_diameters = ["130 um", "270 um"]
psd_passing = [0.0, 1.0]
seed = 1

[dem.preparation]              # isotropic compaction at 1 deg friction to the surcharge
pressure = "{pressure / 1e3:g} kPa"
friction_angle = "1 deg"
inertial_number = 1e-2

[dem.coupling]
inertial_number = 4e-3         # I_n of eq. 11 (as the biaxial)
pressure_floor = "5 kPa"       # T_p of an RVE that loses its contacts (by the footing's edge)
# dt_refresh = 20              # the critical time step kept over 20 DEM steps: 1.29x on this
                               # footing on top of the defaults, errors inside its sensitivity
                               # (docs/validation/speed.md, "Defaults")

[mpm]
shape_function = "ugimp"       # in the plane; linear through the thickness
update = "usf"
plane_strain = "y"             # one cell through y, [2, 1, 2] points per cell
flip = 1.0
position_update = "grid"       # points move with the grid velocity, which the footing holds
strain_smoothing = "cell"      # selective reduced integration per cell (anti-locking under the rough footing)
damping = {damping:g}                  # Cundall damping (eq. 8): a force on the moving nodes that no
                               # reaction reports (with 0.2 the reactions and the surcharge miss
                               # equilibrium by 1-2 % of the footing's load; with 0: 0.2 %)
mass_scaling = 10000           # quasi-static: inertia x 10000, time step x 100
cfl = 0.5
end_time = "{t_end:g} s"

[mpm.grid]                     # one empty cell left of the symmetry plane, beyond the far side and
origin = [{fmt(x0)}, 0.0, {fmt(z0)}]    # under the base (uGIMP), two above the surface (the footing's planes)
spacing = [{fmt(cell)}, {fmt(cell)}, {fmt(cell)}]
cells = [{nx + 2}, 1, {nz + 3}]

[[mpm.body]]
min = [0.0, 0.0, 0.0]
max = [{fmt(width)}, {fmt(cell)}, {fmt(depth)}]
points_per_cell = [2, 1, 2]
density = "1696 kg/m^3"
material = "dem"

[[mpm.velocity]]               # rough rigid base: the node planes z = 0 and under it
min = [{fmt(x0)}, 0.0, {fmt(z0)}]
max = [{fmt(xt)}, {fmt(cell)}, 0.0]
x = 0.0
z = 0.0
name = "base"

[[mpm.velocity]]               # symmetry plane: the node planes x = 0 and left of it
min = [{fmt(x0)}, 0.0, {fmt(z0)}]
max = [0.0, {fmt(cell)}, {fmt(zt)}]
x = 0.0
name = "symmetry"

[[mpm.velocity]]               # far side: roller
min = [{fmt(width)}, 0.0, {fmt(z0)}]
max = [{fmt(xt)}, {fmt(cell)}, {fmt(zt)}]
x = 0.0
name = "far"

[[mpm.velocity]]               # the footing: rigid, rough (no slip), pushed down
min = [{fmt(x0)}, 0.0, {fmt(depth)}]
max = [{fmt(half_width)}, {fmt(cell)}, {fmt(zt)}]
x = 0.0
z = "{-speed * 1e3:g} mm/s"
name = "footing"

[[mpm.traction]]               # the surcharge on the surface's current area (under the footing too:
face = "z+"                    # the footing's reaction includes it over its half-width)
pressure = "{pressure / 1e3:g} kPa"

[output]
every = {every}
'''


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    for k, v in DEFAULTS.items():
        ap.add_argument("--" + k.replace("_", "-"), type=type(v), default=v)
    ap.add_argument("--out", help="the job file to write (default: stdout)")
    ap.add_argument("--check", help="exit 1 unless this file is what the defaults write")
    a = ap.parse_args()
    try:
        text = job_text(**{k: getattr(a, k) for k in DEFAULTS})
    except ValueError as e:
        sys.exit("footing_make_job.py: %s" % e)
    if a.check:
        if open(a.check).read() != text:
            sys.exit("%s differs from what tools/footing_make_job.py writes with its defaults" % a.check)
        return
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
