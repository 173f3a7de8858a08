#!/usr/bin/python3
"""Write jobs/biaxial_plane_strain_<nx>x<nz>.toml: the plane-strain biaxial test
(section 2) on one mesh. The jobs in jobs/ (2 x 4 to 16 x 32) were written by this script; a
user changes the mesh, the RVE size or the rate here, or edits a written job.

    tools/mpmxdem-tools biaxial_make_jobs --mesh 8 16 --strain 0.105 --every 40 --out x.toml
    tools/mpmxdem-tools biaxial_make_jobs --self-test   # the platen keeps its grip (ctest)
"""
import argparse
import math

W, H = 0.05, 0.10  # specimen width (x) and height (z) [m]: 1:2
P = 100e3  # confinement [Pa]
RHO_BULK = 1696.0  # 2650 / (1 + e0), e0 = 0.56 [kg/m^3]


def platen_keys(platen, side=None):
    """The keys that make a node plane a platen: rough (no slip: x = 0), smooth (x free) or a
    Coulomb wall of friction coefficient `platen` (a number), pushed against (contact fixed)."""
    if platen == "rough":
        return "x = 0.0\n"
    if platen == "smooth":
        return ""
    normal = f'normal = "{side}"\n' if side else ""
    return f'friction = {float(platen):g}\n{normal}contact = "fixed"\n'


def end_time(strain, v):
    """The time at which the platen, at speed v, reaches log axial strain `strain` [s]:
    -ln(1 - v t / H) = strain."""
    return H * (1.0 - math.exp(-strain)) / v


def staircase(top, h, v, t_end, lead=0.5):
    """A rigid platen or footing pushed at v into material on a fixed grid, as a staircase of held
    node planes: boxes (k, z_k, t_k), box k holding the nodes at z >= z_k = top - k h from t_k =
    (k - lead) h / v, i.e. `lead` of a cell before the material's top (top - v t) reaches z_k.
    The material above a newly held plane (half a cell) moves with the platen. A node held by
    several boxes keeps its first constraint's reaction: the platen's reaction is the sum over
    its boxes. Also tools/mpmxdem_tools/jobs/footing_make_job.py's footing."""
    boxes = []
    k = 0
    while True:
        tk = max(k - lead, 0.0) * h / v
        if tk >= t_end:
            return boxes
        boxes.append((k, top - k * h, tk))
        k += 1


def grip_failures(top, h, v, t_end, boxes, row_depth, samples=4000):
    """Times at which the top row of points, row_depth(t) below `top`, lies in a cell whose upper
    node plane no box holds yet, or a box engages more than half a cell inside the material (whose
    top is at top - v t). Empty: the staircase keeps its grip."""
    bad = []
    engaged = {k: tk for k, _, tk in boxes}
    for i in range(samples + 1):
        t = t_end * i / samples
        k_cell = math.floor(row_depth(t) / h + 1e-9)  # upper plane of its cell: top - k_cell h
        if not (k_cell in engaged and engaged[k_cell] <= t + 1e-12):
            bad.append(("loose", t))
    for k, zk, tk in boxes:
        if (top - v * tk) - zk > 0.5 * h + 1e-9:
            bad.append(("deep", tk))
    return bad


def platen_boxes(h, v, t_end, lead=0.5):
    """The top platen's boxes (staircase from the specimen's top H). The top row of points (a
    quarter cell under the top) must never leave the cells whose upper node plane is held: with
    lead = 0 (as written before 2026-11-25) it did from 3/4 h to h of travel and the fine meshes
    broke up there (docs/notes/biaxial_2026-11.md, "Three meshes to 10 %")."""
    return staircase(H, h, v, t_end, lead)


def platen_grip_failures(h, v, t_end, boxes, samples=4000):
    """grip_failures of the platen: the top row of points compresses affinely, at (H - h/4)(1 - v t / H)."""
    return grip_failures(H, h, v, t_end, boxes, lambda t: H - (H - h / 4) * (1.0 - v * t / H), samples)


def self_test():
    for nx in (2, 3, 4, 6, 8, 16):
        h = W / nx
        for strain, rate in ((0.105, 0.03), (0.25, 0.01)):
            v = rate * H
            t_end = end_time(strain, v)
            bad = platen_grip_failures(h, v, t_end, platen_boxes(h, v, t_end))
            assert not bad, f"{nx} x {2 * nx} to {strain}: {bad[:3]}"
    # The old staircase (lead 0) loses the grip on 8 x 16 at 10.5 % (from 3/4 h of travel): the
    # check sees it.
    h, v = W / 8, 0.03 * H
    t_end = end_time(0.105, v)
    old = platen_grip_failures(h, v, t_end, platen_boxes(h, v, t_end, lead=0.0))
    assert old and abs(old[0][1] * v - 0.75 * h) < 0.02 * h, old[:2]
    print("biaxial_make_jobs self-test: the platen keeps its grip on 2 x 4 to 16 x 32 meshes to "
          f"25 %; the old staircase loses it on 8 x 16 at {100 * old[0][1] * v / H:.2f} % of travel")


def job(nx, nz, spheres, strain, rate, samples, pad, mass_scaling, every, header, platen="rough",
        smoothing="cell", shape="ugimp", reg_mm=0.0, reg_mpa=0.0, material="dem", friction_angle=40.0, softening=None,
        draw="scattered", seed=1):
    """softening: None, or (residual friction angle [deg], softening strain [-]) of the frictional
    continuum. draw: how the points draw the samples (dem.initial_state.sample_draw); seed: the first
    sample's seed (dem.sample.seed; scattered, also the draw's)."""
    h = W / nx
    assert abs(H / nz - h) < 1e-12, "square cells: nz = 2 nx"
    v = rate * H  # platen speed [m/s]
    t_end = end_time(strain, v)
    x0, x1 = -pad * h, W + pad * h
    # uGIMP: one cell under the base too (a domain on the grid's boundary is refused), held with it.
    below = 1 if shape == "ugimp" else 0
    shape_note = "" if shape == "linear" else "  # in the plane; linear through the thickness"
    grid_note = ", one under the base (uGIMP)" if below else ""
    if below:
        base_where = (f"min = [{x0!r}, 0.0, {-h!r}]       # the node planes z = 0 and the one under it\n"
                      f"max = [{x1!r}, {h!r}, 0.0]\n")
    else:
        base_where = 'face = "z-"\n'
    initial_stress = '\ninitial_stress = ["-100 kPa", "-100 kPa", "-100 kPa", 0.0, 0.0, 0.0]'
    if material == "frictional":
        title = (f"Plane-strain biaxial, frictional continuum (Drucker-Prager, {friction_angle:g} deg"
                 + (f" softening to {softening[0]:g} deg" if softening else "") + f"), {nx} x {nz} cells")
    else:
        title = f"Plane-strain biaxial, MPM x DEM, {nx} x {nz} cells, {4 * nx * nz} RVEs of {spheres} spheres"
    if reg_mm > 0:
        title += f", regularised (l = {reg_mm:g} mm, H = {reg_mpa:g} MPa)"
    reg_table = "" if reg_mm <= 0 else (
        f"""
[mpm.regularisation]           # nonlocal strain gradient: the band's thickness from l, not the cell
length = "{reg_mm:g} mm"              # (docs/design/mpm.md, Regularisation)
modulus = "{reg_mpa:g} MPa"
""")
    layout = f" (point id mod {samples})" if draw == "in_turn" else ", scattered over the points"
    draw_line = "" if draw == "in_turn" else (
        f'sample_draw = "scattered"      # not "in_turn" (point id mod {samples}): that lays them out in a pattern set\n'
        '                               # by the row\'s length (stripes on 8 x 16)\n')
    dem_tables = """[dem.material]                 # the reference material (docs/validation/triaxial.md)
density = "2650 kg/m^3"
young_modulus = "300 MPa"
stiffness_ratio = 0.5
friction_angle = "30 deg"
rolling_stiffness = 2.0
rolling_strength = 0.3

""" + f"""[dem.sample]                   # generated; sample k of the pool has seed {seed} + k
spheres = {spheres}
psd_diameters = ["130 um", "270 um"]
psd_passing = [0.0, 1.0]
seed = {seed}

[dem.preparation]              # isotropic compaction at 1 deg friction to 100 kPa (e0 about 0.56)
pressure = "100 kPa"
friction_angle = "1 deg"
inertial_number = 1e-2

[dem.initial_state]
samples = {samples}                   # distinct RVEs{layout}: the imperfection that lets a band form
{draw_line}
[dem.coupling]
inertial_number = 4e-3         # I_n of eq. 11 (as jobs/triaxial_mpmxdem_distinct.toml)
pressure_floor = "10 kPa"      # T_p of an RVE that loses its contacts (the corners under the rough
                               # platens dilate to p = 0): with 1 kPa those few RVEs took most of
                               # the run (up to 5700 DEM steps per MPM step, docs/validation/biaxial.md)
"""
    elastic_table = f"""[mpm.elastic]                  # elastic-perfectly plastic Drucker-Prager (plane-strain Mohr-Coulomb), no dilatancy
young_modulus = "50 MPa"
poisson_ratio = 0.3
friction_angle = "{friction_angle:g} deg"
"""
    if softening:
        elastic_table = elastic_table.replace("elastic-perfectly plastic", "elastic-plastic, friction softening,")
        elastic_table += (f'residual_friction_angle = "{softening[0]:g} deg"\n'
                          f"softening_strain = {softening[1]:g}         # accumulated plastic shear strain to the residual\n")
    lines = [header.rstrip(), f'title = "{title}"', "",
             elastic_table if material == "frictional" else dem_tables,
             f"""[mpm]
shape_function = "{shape}"{shape_note}
update = "usf"
plane_strain = "y"             # one cell through y, [2, 1, 2] points per cell
flip = 1.0
position_update = "grid"       # points move with the grid velocity, which the platens hold: a FLIP
                               # velocity carried corner points through the platens on fine meshes
strain_smoothing = "{smoothing}"     # cell: selective reduced integration per cell; without it the rough
                               # platens lock the dilatant specimen (docs/validation/biaxial.md, "Locking")
damping = 0.2                  # Cundall damping (eq. 8)
mass_scaling = {mass_scaling:g}           # quasi-static: inertia x {mass_scaling:g}, time step x {math.sqrt(mass_scaling):g}; the log checks E_kin/W_int < 0.01
cfl = 0.5
end_time = "{t_end!r} s"        # log axial strain {strain:g} at the platen speed below
{reg_table}
[mpm.grid]                     # {pad} empty cell(s) each side in x for the lateral expansion, one above
origin = [{x0!r}, 0.0, {-below * h!r}]  # the top (a point next to the platen may drift above it){grid_note}
spacing = [{h!r}, {h!r}, {h!r}]
cells = [{nx + 2 * pad}, 1, {nz + 1 + below}]

[[mpm.body]]
min = [0.0, 0.0, 0.0]
max = [{W:g}, {h!r}, {H:g}]
points_per_cell = [2, 1, 2]
density = "{RHO_BULK:g} kg/m^3"
material = "{material if material == 'dem' else 'elastic'}"{initial_stress if material == 'frictional' else ''}

# Rough rigid platens: no slip (x = 0) and the normal velocity imposed on the whole node plane
# (plain constraints, bonded: the specimen is pushed against them throughout). The base first.
[[mpm.velocity]]
{base_where}{platen_keys(platen, "z-" if below else None)}z = 0.0
name = "base"
""" + ("" if platen != "smooth" else f"""
[[mpm.velocity]]               # smooth platens: one node pinned in x against the rigid motion
node = [{W / 2:g}, 0.0, 0.0]
x = 0.0
"""),
             ]
    for k, zk, tk in platen_boxes(h, v, t_end):
        lines.append(f"""[[mpm.velocity]]
min = [{x0!r}, 0.0, {zk!r}]
max = [{x1!r}, {h!r}, {H + 1.5 * h!r}]
{platen_keys(platen, "z+")}z = "{-v * 1e3!r} mm/s"{'' if k == 0 else f'''
from = "{tk!r} s"'''}
name = "platen_{k}"
""")
    lines.append("""[[mpm.traction]]               # confinement on the free sides, on their current area
face = "x-"
pressure = "100 kPa"

[[mpm.traction]]
face = "x+"
pressure = "100 kPa"
""")
    lines.append(f"""[output]
every = {every}
""")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--mesh", nargs=2, type=int, metavar=("NX", "NZ"))
    ap.add_argument("--spheres", type=int, default=300)
    ap.add_argument("--strain", type=float, default=0.12)
    ap.add_argument("--rate", type=float, default=0.03, help="axial strain rate V/H [1/s]")
    ap.add_argument("--samples", type=int, default=16)
    ap.add_argument("--draw", default="scattered", choices=["in_turn", "scattered"],
                    help="dem.initial_state.sample_draw: scattered (no pattern in space, the jobs in jobs/) or "
                         "in_turn (point id mod samples: stripes where a row holds a multiple of samples)")
    ap.add_argument("--seed", type=int, default=1,
                    help="dem.sample.seed: the samples are seeds SEED to SEED + samples - 1 (and a "
                         "scattered draw depends on it); default 1, the pure-DEM reference's samples")
    ap.add_argument("--pad", type=int, default=None,
                    help="empty cells each side in x (default: enough for 25 mm, half the width)")
    ap.add_argument("--mass-scaling", type=float, default=1e4)
    ap.add_argument("--every", type=int, default=50)
    ap.add_argument("--platen", default="rough", help="rough (no slip), smooth, or a friction coefficient")
    ap.add_argument("--smoothing", default="cell", help="mpm.strain_smoothing: cell or none")
    ap.add_argument("--shape", default="ugimp", choices=["linear", "ugimp"],
                    help="mpm.shape_function (ugimp, the default since 2026-11-25: the grid gets a "
                         "cell under the base; linear: the jobs of before, docs/validation/biaxial.md)")
    ap.add_argument("--regularisation", type=float, nargs=2, default=[0.0, 0.0],
                    metavar=("L_MM", "H_MPA"),
                    help="mpm.regularisation length [mm] and modulus [MPa] (default: none)")
    ap.add_argument("--material", default="dem", choices=["dem", "frictional"],
                    help="dem: every point an RVE; frictional: the Drucker-Prager continuum "
                         "(mpm.elastic with friction_angle), a cheap reference for the mesh studies")
    ap.add_argument("--friction-angle", type=float, default=40.0, help="frictional: phi [deg]")
    ap.add_argument("--softening", type=float, nargs=2, default=None, metavar=("PHI_R_DEG", "GAMMA"),
                    help="frictional: friction softening to the residual angle PHI_R_DEG, reached at "
                         "the accumulated plastic shear strain GAMMA (default: none)")
    ap.add_argument("--header", default="")
    ap.add_argument("--out")
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.self_test:
        self_test()
        return
    if a.pad is None:
        a.pad = math.ceil(0.025 / (W / a.mesh[0]) - 1e-9)
    text = job(a.mesh[0], a.mesh[1], a.spheres, a.strain, a.rate, a.samples, a.pad,
               a.mass_scaling, a.every, a.header, a.platen,
               a.smoothing, a.shape, a.regularisation[0], a.regularisation[1], a.material, a.friction_angle,
               a.softening, a.draw, a.seed)
    open(a.out, "w").write(text)


if __name__ == "__main__":
    main()
