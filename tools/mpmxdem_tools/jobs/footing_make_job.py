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

The grid is fixed and the material under the footing moves down, so the footing is a staircase
of held node planes (boxes footing, footing_1, ...), each taking over the next plane down half a
cell before the material's top reaches it, as the biaxial's platen (tools/mpmxdem_tools/jobs/biaxial_make_jobs.py):
the top row of points under the footing never leaves the cells whose upper plane is held
(--self-test checks it), and the settlement may be many cells. The footing's reaction is the sum
over the boxes (tools/mpmxdem_tools/analysis/footing_curves.py).

--lead L (0.25-0.75 cells, default 0.5) holds each plane L cells before the material's top
reaches it. With 0.5 the lowest held plane is on average at the footing's base, but just before
the next plane takes over the top row of points lies 0.75 of a cell under it, weakly held; with
0.75 it is never more than half a cell under, and the footing is on average a quarter cell
deeper (docs/validation/footing.md, "The RVEs' footing": the RVE layer's deep collapse after its
peak is that weak grip's; with 0.75 the load before it is 3-9 % higher, the peak the same
within 2 %).

--footing-side free ends the footing's held node columns at the surface (by default they reach
the grid's top, and drag the material that heaves beside the footing's edge); --footing-base
smooth imposes only the footing's vertical velocity (no x = 0 on its nodes).

--cfl sets mpm.cfl (0.5 by default). The RVE layer pushed deep needs 0.25: with 0.5 a row of
points settling on a node plane under the footing absorbed work no load gave, somewhere between
s/B = 0.08 and 0.31 in the runs of docs/validation/footing.md ("The RVEs' footing").

--sparing TOL (RVEs only) writes [dem.sparing] tolerance = TOL: the idle far field of a large layer
is predicted by its RVEs' tangents instead of stepped (docs/design/sparing.md; 1e-5 spared 87-92 %
of the RVE steps of layers of 400 x 200 mm and more pushed to s/B = 0.4, docs/validation/footing.md).

--material frictional puts the Drucker-Prager continuum of [mpm.elastic] (plane-strain
Mohr-Coulomb, no dilatancy) in place of the RVEs, at the same isotropic initial stress: the
footing whose limit load bearing-capacity theory gives (tools/mpmxdem_tools/analysis/bearing_capacity.py).

    tools/mpmxdem-tools footing_make_job --out jobs/footing_plane_strain.toml
    tools/mpmxdem-tools footing_make_job --width 0.4 --depth 0.2 --out /tmp/footing_wide.toml
    tools/mpmxdem-tools footing_make_job --material frictional --settlement 0.015 --out /tmp/f.toml
    tools/mpmxdem-tools footing_make_job --check jobs/footing_plane_strain.toml  # (ctest)
    tools/mpmxdem-tools footing_make_job --self-test                          # (ctest)
"""
import argparse
import math
import re
import sys

from .biaxial_make_jobs import grip_failures, staircase

DEFAULTS = dict(width=0.2, depth=0.1, cell=0.0125, half_width=0.025, settlement=0.005,
                speed=0.001, spheres=100, pressure=50e3, every=10, damping=0.2, material="dem",
                friction_angle=40.0, young=50e6, above=2, mass_scaling=10000.0, dilatancy_angle=0.0,
                footing_side="held", footing_base="rough", regularisation_length=0.0,
                regularisation_modulus=0.0, cfl=0.5, sparing=0.0, lead=0.5)
# lead: a plane is held this many cells before the material's top reaches it. The top row of points
# under the footing (a quarter cell under the material's top) then lies down to 1.25 - lead cells
# under the lowest held plane before the next one takes over (0.75 with the default 0.5); with a lead
# above 0.5 a plane engages lead - 0.5 cells deeper inside the material than the default.


def footing_boxes(depth, cell, speed, t_end, lead=0.5):
    """The footing's boxes (k, z_k, t_k): box k holds the node planes z >= depth - k cell from
    t_k = (k - lead) cell / speed (box 0 from the start)."""
    if not 0.25 <= lead <= 0.75:
        raise ValueError("lead must be in [0.25, 0.75] cells: with less the top row of points leaves the held "
                         "planes' cells, with more a plane engages with a whole row of points above it")
    return staircase(depth, cell, speed, t_end, lead)


def footing_grip_failures(depth, cell, speed, t_end, boxes, samples=4000):
    """grip_failures of the footing: the top row of points under it, a quarter cell under the
    surface, moves down with it."""
    return grip_failures(depth, cell, speed, t_end, boxes, lambda t: cell / 4 + speed * t, samples)


def self_test():
    for cell in (0.025, 0.0125, 0.00625):
        for settlement in (0.005, 0.015, 0.03):
            t_end = settlement / 0.001
            for lead in (0.25, 0.375, 0.5):
                bad = footing_grip_failures(0.1, cell, 0.001, t_end, footing_boxes(0.1, cell, 0.001, t_end, lead))
                assert not bad, f"cell {cell} to {settlement}, lead {lead}: {bad[:3]}"
    # A lead of 0.75 keeps the top row within half a cell of a held plane; its planes engage a
    # quarter cell deeper than grip_failures' half a cell (the only failures it reports).
    bad = footing_grip_failures(0.1, 0.0125, 0.001, 30.0, footing_boxes(0.1, 0.0125, 0.001, 30.0, 0.75))
    assert bad and all(kind == "deep" for kind, _ in bad), bad
    # Below 0.25 the top row leaves the held planes' cells: refused, as is a lead above 0.75.
    bad = footing_grip_failures(0.1, 0.0125, 0.001, 30.0, staircase(0.1, 0.0125, 0.001, 30.0, 0.2))
    assert bad and all(kind == "loose" for kind, _ in bad), bad
    for lead in (0.2, 0.8):
        try:
            footing_boxes(0.1, 0.0125, 0.001, 30.0, lead)
            raise AssertionError("lead %g was accepted" % lead)
        except ValueError:
            pass
    # One plane (no staircase) loses the grip three quarters of a cell down: the check sees it.
    t_end = 0.03 / 0.001
    bad = footing_grip_failures(0.1, 0.0125, 0.001, t_end, [(0, 0.1, 0.0)])
    assert bad and abs(bad[0][1] * 0.001 - 0.75 * 0.0125) < 1e-4, bad[:2]
    # The footing's sides and base: "held" boxes reach the grid's top, "free" ones hold their own
    # plane only (together every plane from the lowest engaged one up to the surface, none above);
    # a smooth base imposes no x velocity.
    held = footing_velocity_tables(-0.0125, 0.125, 0.1, 0.0125, 0.025, 0.001, 30.0)
    free = footing_velocity_tables(-0.0125, 0.125, 0.1, 0.0125, 0.025, 0.001, 30.0, "free", "smooth")
    tops = [float(m) for m in re.findall(r"^max = \[[^,]+, [^,]+, ([^\]]+)\]$", held, re.M)]
    assert tops and all(abs(t - 0.125) < 1e-12 for t in tops), tops
    lo = [float(m) for m in re.findall(r"^min = \[[^,]+, [^,]+, ([^\]]+)\]$", free, re.M)]
    hi = [float(m) for m in re.findall(r"^max = \[[^,]+, [^,]+, ([^\]]+)\]$", free, re.M)]
    assert lo == hi and max(hi) == 0.1 and len(hi) == len(tops), (lo, hi)
    assert all(abs(a - b - 0.0125) < 1e-12 for a, b in zip(hi, hi[1:])), hi
    assert "\nx = 0.0" in held and "\nx = 0.0" not in free
    # A material length: the [mpm.regularisation] table in SI units' words, both keys or neither.
    base = dict(DEFAULTS, material="frictional")
    assert "[mpm.regularisation]" not in job_text(**base)
    reg = job_text(**dict(base, regularisation_length=0.02, regularisation_modulus=1e6))
    assert re.search(r'^\[mpm\.regularisation\].*\nlength = "20 mm"\nmodulus = "1 MPa"$', reg, re.M), reg
    try:
        job_text(**dict(base, regularisation_length=0.02))
        raise AssertionError("a length without a modulus was accepted")
    except ValueError:
        pass
    print("footing_make_job self-test: the footing keeps its grip on cells of 25 / 12.5 / 6.25 mm "
          "to 30 mm of settlement; one held plane loses it %.2f cell down" % (bad[0][1] * 0.001 / 0.0125))


def fmt(x):
    """A length as it reads best in a job (no float noise): 0.0125, not 0.012500000000000001."""
    return repr(round(x, 12))


def material_tables(material, spheres, pressure, friction_angle, young, dilatancy_angle=0.0):
    """The tables that say what the layer is made of: RVEs, or the Drucker-Prager continuum."""
    if material == "frictional":
        if dilatancy_angle == 0:
            return f'''[mpm.elastic]                  # elastic-perfectly plastic Drucker-Prager (plane-strain Mohr-Coulomb), no dilatancy
young_modulus = "{young / 1e6:g} MPa"
poisson_ratio = 0.3
friction_angle = "{friction_angle:g} deg"
'''
        return f'''[mpm.elastic]                  # elastic-perfectly plastic Drucker-Prager (plane-strain Mohr-Coulomb)
young_modulus = "{young / 1e6:g} MPa"
poisson_ratio = 0.3
friction_angle = "{friction_angle:g} deg"
dilatancy_angle = "{dilatancy_angle:g} deg"{'      # associated flow' if dilatancy_angle == friction_angle else ''}
'''
    if material != "dem":
        raise ValueError("material must be dem or frictional, not %r" % material)
    return f'''[dem.material]                 # the reference material (docs/validation/triaxial.md)
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
'''


def footing_velocity_tables(x0, zt, depth, cell, half_width, speed, t_end, side="held", base="rough", lead=0.5):
    """The footing: box 0 on the surface's node plane, then one box per plane down (staircase).
    side "held": each box holds its node columns from its plane up to the grid's top zt, so the
    material that heaves beside the footing's edge above the surface is dragged by the edge column
    (a footing with a rough vertical side); "free": each box holds its own plane only (the boxes
    together hold the planes from the lowest engaged one up to the surface, all the material under
    the footing needs: no node above the surface is held, the heave beside the edge is free).
    base "rough": the held nodes move with the footing in x too (no slip); "smooth": only their
    vertical velocity is imposed (for a weightless layer Prandtl's N_q is the same for both)."""
    if side not in ("held", "free"):
        raise ValueError("footing_side must be held or free, not %r" % side)
    if base not in ("rough", "smooth"):
        raise ValueError("footing_base must be rough or smooth, not %r" % base)
    slip = "x = 0.0\n" if base == "rough" else ""
    out = []
    for k, zk, tk in footing_boxes(depth, cell, speed, t_end, lead):
        top = zt if side == "held" else zk
        head = (f"[[mpm.velocity]]               # the footing: rigid, {base}{' (no slip)' if base == 'rough' else ''}, pushed down" if k == 0
                else f"[[mpm.velocity]]               # the footing's next node plane, held from {tk:g} s")
        since = "" if k == 0 else f'\nfrom = "{fmt(tk)} s"'
        name = "footing" if k == 0 else "footing_%d" % k
        out.append(f'''{head}
min = [{fmt(x0)}, 0.0, {fmt(zk)}]
max = [{fmt(half_width)}, {fmt(cell)}, {fmt(top)}]
{slip}z = "{-speed * 1e3:g} mm/s"{since}
name = "{name}"
''')
    return "\n".join(out)


def job_text(width, depth, cell, half_width, settlement, speed, spheres, pressure, every, damping,
             material="dem", friction_angle=40.0, young=50e6, above=2, mass_scaling=10000.0,
             dilatancy_angle=0.0, footing_side="held", footing_base="rough", regularisation_length=0.0,
             regularisation_modulus=0.0, cfl=0.5, sparing=0.0, lead=0.5):
    nx, nz = round(width / cell), round(depth / cell)
    if abs(nx * cell - width) > 1e-9 * width or abs(nz * cell - depth) > 1e-9 * depth:
        raise ValueError("width and depth must be whole numbers of cells")
    if abs(round(half_width / cell) * cell - half_width) > 1e-9 or half_width < cell:
        raise ValueError("half_width must be a whole number (>= 1) of cells")
    if settlement >= depth / 2:
        raise ValueError("settlement %g m is half the layer's depth (%g m) or more" % (settlement, depth))
    rves = nx * nz * 4
    t_end = settlement / speed
    x0, z0 = -cell, -cell                     # one empty cell left of x = 0 and under the base
    xt, zt = width + cell, depth + above * cell  # one beyond the far side, `above` above the surface
    B_mm = 2e3 * half_width
    init_stress = f'''
initial_stress = ["-{pressure / 1e3:g} kPa", "-{pressure / 1e3:g} kPa", "-{pressure / 1e3:g} kPa", 0.0, 0.0, 0.0]'''
    frictional = material == "frictional"
    above_words = "two" if above == 2 else "%d" % above
    if above < 2:
        raise ValueError("above must be 2 cells or more (the footing's planes)")
    flags = "" if not frictional else (
        f"\n#   --material frictional --friction-angle {friction_angle:g} --young {young:g}")
    flags += "" if dilatancy_angle == 0 else f" --dilatancy-angle {dilatancy_angle:g}"
    flags += "" if above == 2 else f" --above {above}"
    flags += "" if mass_scaling == 10000 else f" --mass-scaling {mass_scaling:g}"
    flags += "" if footing_side == "held" else f" --footing-side {footing_side}"
    flags += "" if footing_base == "rough" else f" --footing-base {footing_base}"
    flags += "" if cfl == 0.5 else f" --cfl {cfl:g}"
    flags += "" if lead == 0.5 else f" --lead {lead:g}"
    sparing_table = ""
    if sparing > 0:
        if frictional:
            raise ValueError("sparing is for the RVEs (material dem)")
        flags += f" --sparing {sparing:g}"
        sparing_table = f"""
[dem.sparing]                  # idle RVEs (the far field) predicted by their tangent (docs/design/sparing.md)
tolerance = {sparing:g}
"""
    if (regularisation_length > 0) != (regularisation_modulus > 0):
        raise ValueError("regularisation_length and regularisation_modulus go together")
    reg_table = ""
    if regularisation_length > 0:
        flags += (f"\n#   --regularisation-length {regularisation_length:g}"
                  f" --regularisation-modulus {regularisation_modulus:g}")
        reg_table = f"""
[mpm.regularisation]           # nonlocal strain gradient: a material length l (docs/design/mpm.md)
length = "{regularisation_length * 1e3:g} mm"
modulus = "{regularisation_modulus / 1e6:g} MPa"
"""
    what = (f"{nx} x {nz} cells of [2, 1, 2] points ({rves} RVEs of {spheres} spheres)" if not frictional else
            f"{nx} x {nz} cells of [2, 1, 2] points (Drucker-Prager, phi = {friction_angle:g} deg, "
            + ("no dilatancy)" if dilatancy_angle == 0 else f"psi = {dilatancy_angle:g} deg)"))
    state = ("(one\n# DEM preparation for every RVE)" if not frictional else "(the\n# continuum's initial stress)")
    title = (f"Plane-strain strip footing, MPM x DEM, {nx} x {nz} cells, {rves} RVEs of {spheres} spheres"
             if not frictional else
             f"Plane-strain strip footing, Drucker-Prager continuum ({friction_angle:g} deg), {nx} x {nz} cells")
    return f'''# Plane-strain strip footing on a granular layer (a scene whose far field idles).
# Written by tools/mpmxdem-tools footing_make_job --width {width:g} --depth {depth:g} --cell {cell:g} --half-width {half_width:g}
#   --settlement {settlement:g} --speed {speed:g} --spheres {spheres} --pressure {pressure:g} --every {every}
#   --damping {damping:g}{flags}
# Half of the problem (symmetry plane x = 0): a layer {width * 1e3:g} mm wide and {depth * 1e3:g} mm deep on
# {what}, a rigid rough footing of
# half-width {half_width * 1e3:g} mm (B = {B_mm:g} mm: the node columns x = 0 ... {half_width * 1e3:g} mm of the surface)
# pushed down at {speed * 1e3:g} mm/s to a settlement of {settlement * 1e3:g} mm ({settlement / (2 * half_width):g} B). No gravity: a
# {pressure / 1e3:g} kPa surcharge on the surface and an isotropic initial state at {pressure / 1e3:g} kPa {state}; rollers on the sides (x = 0: symmetry; x = {width * 1e3:g} mm: far field),
# a rough rigid base. Mass scaling {"1e4" if mass_scaling == 1e4 else f"{mass_scaling:g}"} (quasi-static: the log reports E_kin/W_int).
# Reference quantity: the footing's reaction (reactions.csv footing_rz_N) against its settlement
# (footing_uz_m); its bearing pressure is -footing_rz_N / (half-width x thickness {cell * 1e3:g} mm)
# (tools/mpmxdem_tools/analysis/footing_curves.py). The default layer (200 x 100 mm, 2 B deep on a rough base) is small:
# at 0.1 B it carries 6.7 MPa against 4.8 and 4.4 on layers 2 and 3 times as wide and deep; study
# the footing itself on the larger ones (--width 0.6 --depth 0.3: 4608 RVEs, about 4 min on 2 cores).
# Sparing the idle far field: docs/validation/speed.md "Sparing on a strip footing".
#
# Run:        mpirun -n 2 --bind-to none mpmxdem run jobs/footing_plane_strain.toml --out results/footing
# Validate:   mpmxdem check jobs/footing_plane_strain.toml
title = "{title}"

{material_tables(material, spheres, pressure, friction_angle, young, dilatancy_angle)}{sparing_table}
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
mass_scaling = {mass_scaling:g}{' ' * (16 - len('%g' % mass_scaling))}# quasi-static: inertia x {mass_scaling:g}, time step x {math.sqrt(mass_scaling):.3g}
cfl = {cfl:g}
end_time = "{t_end:g} s"
{reg_table}
[mpm.grid]                     # one empty cell left of the symmetry plane, beyond the far side and
origin = [{fmt(x0)}, 0.0, {fmt(z0)}]    # under the base (uGIMP), {above_words} above the surface (the footing's planes)
spacing = [{fmt(cell)}, {fmt(cell)}, {fmt(cell)}]
cells = [{nx + 2}, 1, {nz + 1 + above}]

[[mpm.body]]
min = [0.0, 0.0, 0.0]
max = [{fmt(width)}, {fmt(cell)}, {fmt(depth)}]
points_per_cell = [2, 1, 2]
density = "1696 kg/m^3"
material = "{'elastic' if frictional else 'dem'}"{init_stress if frictional else ''}

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

{footing_velocity_tables(x0, zt, depth, cell, half_width, speed, t_end, footing_side, footing_base, lead)}
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
    # --above: empty cells above the surface (a dilatant layer heaves beside a deep footing)
    ap.add_argument("--check", help="exit 1 unless this file is what the defaults write")
    ap.add_argument("--self-test", action="store_true", help="check the footing's staircase keeps its grip")
    a = ap.parse_args()
    if a.self_test:
        self_test()
        return
    try:
        text = job_text(**{k: getattr(a, k) for k in DEFAULTS})
    except ValueError as e:
        sys.exit("footing_make_job.py: %s" % e)
    if a.check:
        if open(a.check).read() != text:
            sys.exit("%s differs from what tools/mpmxdem_tools/jobs/footing_make_job.py writes with its defaults" % a.check)
        return
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
