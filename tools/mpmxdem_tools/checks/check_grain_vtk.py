#!/usr/bin/python3
"""Checks the grain-scale views that `mpmxdem inspect CKPT --rve ID --vtk DIR` wrote against the
checkpoint they come from (read with h5py).

  tools/mpmxdem-tools check_grain_vtk CKPT DIR [--paraview] [--expect N]

Every DIR/rve_<id>_step_<step>.vtm of the checkpoint's step (at least one; --expect N: exactly N)
is read with Python's xml.etree (no ParaView: cheap, what CI runs) and, with --paraview, also
opened with ParaView's default reader (paraview.simple.OpenDataFile, in a child process: ParaView
bundles its own HDF5). For each RVE, both readers must show:
  spheres   one point per sphere (spheres/r), inside the cell (fractional coordinates in [0, 1))
            and an image of the centre spheres/x (their difference a lattice vector of cell/h);
            arrays id, radius (= spheres/r), velocity (= u + L x at the point, L = cell/l),
            fluctuating_velocity (= spheres/u), spin (= spheres/w), force, torque, contacts
  contacts  one line per active contact (contacts/active); sphere1, sphere2 = contacts/pair; the
            line starts at sphere 1's point and its length is |x2 + H k - x1| (the periodic
            branch: a contact across the boundary is drawn across it, not across the cell);
            normal_force = contacts/normal_force, shear_force = contacts/shear_force,
            rolling_moment = contacts/rolling_moment, force = contacts/force
  cell      one hexahedron with the corners H [0,1]^3; stress = the RVE's stress field
  series    DIR/rve_<id>.pvd lists the view at the checkpoint's time (attribute /time), once
Exit status: 0 every check passed, 1 a check failed, 77 h5py (or, with --paraview, ParaView) is
missing (CTest's skip code). Use /usr/bin/python3 (Debian's python3-h5py, python3-paraview).
"""

import argparse
import glob
import importlib.util
import json
import os
import re
import subprocess
import sys

from ..paths import tool_command

SKIP = 77
SPHERE_ARRAYS = ["contacts", "fluctuating_velocity", "force", "id", "radius", "spin", "torque",
                 "velocity"]
CONTACT_ARRAYS = ["force", "normal", "normal_force", "normal_force_vector", "overlap",
                  "rolling_moment", "shear_force", "shear_force_magnitude", "sphere1", "sphere2",
                  "twisting_moment"]
CELL_ARRAYS = ["fabric", "kinetic_energy", "p", "q", "stress", "unbalanced", "void_ratio",
               "volume", "z", "z_mech"]
HEX_CORNERS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1),
               (0, 1, 1)]


class Failure(Exception):
    pass


def expect(cond, what):
    if not cond:
        raise Failure(what)


def log(msg):
    print("check_grain_vtk: " + msg, flush=True)


# ------------------------------------------------------------------ the checkpoint (h5py)

def read_checkpoint(path, h5py, np):
    """step, ids and a function giving one RVE's fields (name -> flat array)."""
    f = h5py.File(path, "r")
    names = bytes(f["/rve/field_names"][()]).decode().split()
    fields = [n[2:] for n in names]
    ids = f["/rve/ids"][()]

    def rve(rid):
        k = int(np.searchsorted(ids, rid))
        expect(k < len(ids) and ids[k] == rid, f"{path}: no RVE id {rid}")
        out = {}
        for name in fields:
            counts = f["/rve/counts/" + name][()]
            if counts[k] < 0:
                continue
            start = int(np.maximum(counts[:k], 0).sum())
            out[name] = f["/rve/fields/" + name][start:start + counts[k]]
        return out

    return int(f.attrs["step"]), float(f.attrs["time"]), ids, rve


def check_series(path, vtm, time):
    """DIR/rve_<id>.pvd (xml.etree; ParaView's PVD reader with --paraview) lists `vtm` once, at
    the checkpoint's time (17 digits: exactly)."""
    import xml.etree.ElementTree as ET

    expect(os.path.exists(path), f"{path}: missing (the time series of the RVE)")
    root = ET.parse(path).getroot()
    expect(root.get("type") == "Collection", f"{path}: not a VTK collection")
    found = [float(d.get("timestep")) for d in root.iter("DataSet")
             if d.get("file") == os.path.basename(vtm)]
    expect(found == [time], f"{path}: {os.path.basename(vtm)} listed at {found}, expected [{time}]")


# ------------------------------------------------------------------ readers of the views

def read_xml(vtm, np):
    """The view as {block: {points, connectivity, offsets, types, point_data, cell_data}}."""
    import xml.etree.ElementTree as ET

    def values(da):
        kind = int if da.get("type").startswith(("Int", "UInt")) else float
        v = np.array([kind(x) for x in (da.text or "").split()])
        nc = int(da.get("NumberOfComponents", "1"))
        return v.reshape(-1, nc) if nc > 1 else v

    out = {}
    root = ET.parse(vtm).getroot()
    expect(root.get("type") == "vtkMultiBlockDataSet", f"{vtm}: not a multiblock file")
    for ds in root.find("vtkMultiBlockDataSet").findall("DataSet"):
        path = os.path.join(os.path.dirname(vtm), ds.get("file"))
        r = ET.parse(path).getroot()
        piece = r.find(r.get("type") + "/Piece")
        b = {"points": values(piece.find("Points/DataArray")), "point_data": {}, "cell_data": {}}
        for group, key in (("PointData", "point_data"), ("CellData", "cell_data")):
            for da in piece.findall(group + "/DataArray"):
                b[key][da.get("Name")] = values(da)
        b["connectivity"] = b["offsets"] = np.array([], dtype=int)
        for tag, count in (("Lines", "NumberOfLines"), ("Verts", "NumberOfVerts"),
                           ("Cells", "NumberOfCells")):
            cells = piece.find(tag)
            if cells is not None and int(piece.get(count, "0")) > 0:
                for da in cells.findall("DataArray"):
                    b[da.get("Name")] = values(da)
                break
        out[ds.get("name")] = b
    return out


def paraview_child(vtm):
    """Runs in a child process: opens the view with ParaView, prints what it read as JSON."""
    from paraview import servermanager as sm
    from paraview import simple
    from vtk.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet

    reader = simple.OpenDataFile(vtm)
    data = sm.Fetch(reader)
    out = {"reader": reader.GetXMLName(), "blocks": {}}

    def tolist(a):
        return vtk_to_numpy(a).tolist() if a is not None else []

    for k in range(data.GetNumberOfBlocks()):
        name = data.GetMetaData(k).Get(vtkCompositeDataSet.NAME())
        d = data.GetBlock(k)
        b = {"points": tolist(d.GetPoints().GetData()) if d.GetPoints() else [],
             "point_data": {}, "cell_data": {}}
        for src, key in ((d.GetPointData(), "point_data"), (d.GetCellData(), "cell_data")):
            for a in range(src.GetNumberOfArrays()):
                b[key][src.GetArrayName(a)] = tolist(src.GetArray(a))
        if d.IsA("vtkPolyData"):
            cells = d.GetLines() if d.GetNumberOfLines() > 0 else d.GetVerts()
        else:
            cells = d.GetCells()
            b["types"] = tolist(d.GetCellTypesArray())
        b["connectivity"] = tolist(cells.GetConnectivityArray())
        b["offsets"] = tolist(cells.GetOffsetsArray())[1:]  # VTK keeps a leading 0
        out["blocks"][name] = b
    print("PARAVIEW_JSON " + json.dumps(out))


def read_paraview(vtm, np):
    proc = subprocess.run(tool_command("check_grain_vtk") + ["--paraview-child", vtm],
                          capture_output=True, text=True, timeout=600)
    line = [x for x in proc.stdout.splitlines() if x.startswith("PARAVIEW_JSON ")]
    expect(proc.returncode == 0 and line,
           f"{vtm}: ParaView failed ({proc.returncode}): {proc.stderr[-2000:]}")
    got = json.loads(line[0][len("PARAVIEW_JSON "):])
    out = {}
    for name, b in got["blocks"].items():
        c = {"points": np.array(b["points"]), "point_data": {}, "cell_data": {}}
        for key in ("point_data", "cell_data"):
            c[key] = {k: np.array(v) for k, v in b[key].items()}
        for key in ("connectivity", "offsets", "types"):
            if key in b:
                c[key] = np.array(b[key])
        out[name] = c
    return out, got["reader"]


# ------------------------------------------------------------------ the comparison

def vec(a):
    return a.reshape(-1, 3)


def check_view(view, ck, where, np):
    """Compares one RVE's view (either reader) with its checkpoint fields `ck`."""
    expect(sorted(view) == ["cell", "contacts", "spheres"], f"{where}: blocks {sorted(view)}")
    h = ck["cell/h"].reshape(3, 3)
    l = ck["cell/l"].reshape(3, 3)
    hinv = np.linalg.inv(h)
    x = vec(ck["spheres/x"])
    n = len(ck["spheres/r"])

    s = view["spheres"]
    pts = vec(s["points"])
    expect(pts.shape == (n, 3), f"{where}: {pts.shape[0]} sphere points, the checkpoint has {n}")
    expect(sorted(s["point_data"]) == SPHERE_ARRAYS,
           f"{where}: sphere arrays {sorted(s['point_data'])}, expected {SPHERE_ARRAYS}")
    pd = s["point_data"]
    expect(np.array_equal(pd["id"], np.arange(n)), f"{where}: sphere ids are not 0..{n - 1}")
    expect(np.array_equal(pd["radius"], ck["spheres/r"]), f"{where}: radius != spheres/r")
    expect(np.array_equal(vec(pd["spin"]), vec(ck["spheres/w"])), f"{where}: spin != spheres/w")
    expect(np.array_equal(vec(pd["fluctuating_velocity"]), vec(ck["spheres/u"])),
           f"{where}: fluctuating_velocity != spheres/u")
    expect(np.array_equal(vec(pd["force"]), vec(ck["spheres/force"])),
           f"{where}: force != spheres/force")
    frac = pts @ hinv.T
    # Tolerance 1e-12 on fractional coordinates: the wrap x - H m rounds at ~1e-16 of the cell.
    expect(frac.min() >= -1e-12 and frac.max() < 1 + 1e-12,
           f"{where}: a sphere point lies outside the cell (fractional {frac.min()}..{frac.max()})")
    lattice = (x - pts) @ hinv.T
    expect(np.abs(lattice - np.round(lattice)).max() < 1e-9,
           f"{where}: a sphere point is not an image of its centre spheres/x")
    v_ref = vec(ck["spheres/u"]) + pts @ l.T
    # Relative 1e-12: the same sum in C++ and numpy, summation order aside.
    scale = max(np.abs(v_ref).max(), 1e-300)
    expect(np.abs(vec(pd["velocity"]) - v_ref).max() <= 1e-12 * scale,
           f"{where}: velocity != u + L x at the sphere points")

    c = view["contacts"]
    active = ck["contacts/active"] == 1
    nc = int(active.sum())
    pair = ck["contacts/pair"].reshape(-1, 2)[active]
    image = ck["contacts/image"].reshape(-1, 3)[active]
    ends = vec(c["points"])
    expect(ends.shape == (2 * nc, 3), f"{where}: {ends.shape[0] // 2} contact lines, the "
           f"checkpoint has {nc} active contacts")
    expect(np.array_equal(c["connectivity"], np.arange(2 * nc)) and
           np.array_equal(c["offsets"], 2 * np.arange(1, nc + 1)),
           f"{where}: contact lines are not the point pairs (0,1), (2,3), ...")
    expect(sorted(c["cell_data"]) == CONTACT_ARRAYS,
           f"{where}: contact arrays {sorted(c['cell_data'])}, expected {CONTACT_ARRAYS}")
    cd = c["cell_data"]
    expect(np.array_equal(cd["sphere1"], pair[:, 0]) and np.array_equal(cd["sphere2"], pair[:, 1]),
           f"{where}: sphere1, sphere2 != contacts/pair of the active contacts")
    # The normal force is not stored (DEM state version 3): kn (r1 + r2 - |branch|) with the
    # harmonic kn = 2 E r1 E r2 / (E r1 + E r2) of the checkpoint's radii and material, computed
    # here independently; 1e-12 relative: numpy's sum and norm may round differently from Eigen.
    r = ck["spheres/r"]
    # params/material/young_modulus since DEM state version 5, params/material/young before.
    young_name = "params/material/young_modulus"
    young = float(np.asarray(ck[young_name if young_name in ck else "params/material/young"])
                  .reshape(-1)[0])
    r1, r2 = r[pair[:, 0]], r[pair[:, 1]]
    kn = 2.0 * (young * r1) * (young * r2) / (young * r1 + young * r2)
    fn_ref = kn * (r1 + r2 - np.linalg.norm(ck["contacts/branch"].reshape(-1, 3)[active], axis=1))
    fn_got = cd["normal_force"].reshape(nc)
    expect(nc == 0 or np.abs(fn_got - fn_ref).max() <= 1e-12 * np.abs(fn_ref).max(),
           f"{where}: normal_force != kn (r1 + r2 - |branch|) of the active contacts")
    for name, field in (("shear_force", "contacts/shear_force"),
                        ("rolling_moment", "contacts/rolling_moment"),
                        ("twisting_moment", "contacts/twisting_moment"),
                        ("force", "contacts/force"), ("normal", "contacts/normal")):
        ref = ck[field].reshape(len(active), -1)[active]
        got = cd[name].reshape(nc, -1)
        expect(np.array_equal(got, ref), f"{where}: {name} != {field} of the active contacts")
    expect(np.array_equal(ends[0::2], pts[pair[:, 0]]),
           f"{where}: a contact line does not start at its sphere 1's point")
    branch = x[pair[:, 1]] + image @ h.T - x[pair[:, 0]]
    length = np.linalg.norm(ends[1::2] - ends[0::2], axis=1)
    ref_len = np.linalg.norm(branch, axis=1)
    # Relative 1e-9: the branch is a difference of positions ~1e3 times longer than it.
    expect(np.abs(length - ref_len).max() <= 1e-9 * ref_len.max(),
           f"{where}: a contact line is not as long as its periodic branch")
    across = int((np.abs(image).sum(axis=1) > 0).sum())

    cell = view["cell"]
    corners = vec(cell["points"])
    ref = np.array(HEX_CORNERS, dtype=float) @ h.T
    expect(corners.shape == (8, 3) and np.abs(corners - ref).max() <= 1e-12 * np.abs(h).max(),
           f"{where}: the cell's corners are not H [0,1]^3")
    expect(np.array_equal(cell["types"], [12]), f"{where}: the cell is not one hexahedron")
    expect(sorted(cell["cell_data"]) == CELL_ARRAYS,
           f"{where}: cell arrays {sorted(cell['cell_data'])}, expected {CELL_ARRAYS}")
    expect(np.array_equal(cell["cell_data"]["stress"].reshape(9), ck["stress"]),
           f"{where}: cell stress != the RVE's stress")
    return n, nc, across


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--paraview-child":
        paraview_child(sys.argv[2])
        return 0
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("checkpoint")
    ap.add_argument("dir")
    ap.add_argument("--paraview", action="store_true",
                    help="also open every view with ParaView's default reader (required then)")
    ap.add_argument("--expect", type=int, default=None, help="number of RVE views expected")
    a = ap.parse_args()
    for module in ["h5py", "numpy"] + (["paraview.simple"] if a.paraview else []):
        try:
            found = importlib.util.find_spec(module) is not None
        except ModuleNotFoundError:
            found = False
        if not found:
            log(f"{module} is not installed: skipped (use /usr/bin/python3)")
            return SKIP
    import h5py
    import numpy as np

    try:
        step, time, ids, rve = read_checkpoint(a.checkpoint, h5py, np)
        views = []
        for path in sorted(glob.glob(os.path.join(a.dir, "rve_*_step_*.vtm"))):
            m = re.fullmatch(r"rve_(\d+)_step_(\d+)\.vtm", os.path.basename(path))
            if m and int(m.group(2)) == step:
                views.append((int(m.group(1)), path))
        expect(views, f"{a.dir}: no rve_<id>_step_{step}.vtm for the checkpoint's step {step}")
        if a.expect is not None:
            expect(len(views) == a.expect, f"{a.dir}: {len(views)} views, expected {a.expect}")
        leftovers = glob.glob(os.path.join(a.dir, "*.tmp"))
        expect(not leftovers, f"{a.dir}: staged files left behind: {leftovers}")
        for rid, path in sorted(views):
            ck = rve(rid)
            check_series(os.path.join(a.dir, f"rve_{rid}.pvd"), path, time)
            n, nc, across = check_view(read_xml(path, np), ck, path + " (xml.etree)", np)
            readers = "xml.etree"
            if a.paraview:
                view, name = read_paraview(path, np)
                check_view(view, ck, f"{path} (ParaView {name})", np)
                readers += f" and ParaView ({name})"
            log(f"RVE {rid}: {n} spheres, {nc} contacts ({across} across the periodic boundary), "
                f"cell: equal to {os.path.basename(a.checkpoint)} ({readers})")
    except Failure as e:
        log("FAILED: " + str(e))
        return 1
    log(f"{len(views)} view(s) of step {step} agree with the checkpoint")
    return 0


if __name__ == "__main__":
    sys.exit(main())
