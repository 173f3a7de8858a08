#!/usr/bin/python3
"""Opens every output of an `mpmxdem run` directory with the clients researchers use and checks
them against results.h5.

  tools/mpmxdem-tools check_outputs DIR [--require h5py,pandas,paraview] [--without pandas,paraview]

  results.h5          h5py (required): format attributes, every dataset's unit and description,
                      shapes (rows, RVEs, points) consistent, p and q of the points = their RVE's;
                      point fields: displacement = x - x(row 0) when row 0 is step 0, volume =
                      det(F) volume(row 0); grain measures: fabric symmetric with trace 1, Z
                      without rattlers >= Z where Z >= 2, unbalanced force and kinetic energy
                      >= 0, or all NaN (a continuum RVE)
  means.csv           pandas.read_csv if pandas is installed, else csv.DictReader: the first line
                      is the header, one row per results.h5 row, values equal to /step, /time and
                      /means/* (exactly: written with 17 digits)
  points.xmf          ParaView (paraview.simple, its default reader for .xmf) if importable, else
                      ElementTree: one time step per row at /time, every point at /points/x of its
                      row, the arrays id, p, q, stress, void_ratio, z, volume, velocity,
                      displacement, F with results.h5's values
  checkpoint_*.h5     h5py: format attribute, step among the rows' steps
  run_summary.json    json: the run reached its end time (exit 0), its MPM steps and time are the
                      last row's
  job.toml, job.resolved.toml   tomllib

--require names clients whose absence is a failure (default: only h5py). Exit status: 0 all
checks passed, 1 a check failed, 77 a required client is missing (CTest's skip code).
The ParaView part runs in a child process (ParaView bundles its own HDF5; kept apart from h5py's).
Use /usr/bin/python3 (Debian's packages). Clients on Debian 12: python3-h5py (required),
python3-pandas, python3-paraview (no display needed: it only reads).
"""

import argparse
import csv
import glob
import importlib.util
import json
import os
import subprocess
import sys

from ..paths import tool_command
from ..readers import text_attribute as text

SKIP = 77
POINT_ARRAYS = sorted(["id", "p", "q", "stress", "void_ratio", "z", "volume", "velocity",
                       "displacement", "F"])
# Arrays of points.xmf compared value for value with /points/<name> of results.h5.
POINT_VALUES = ["p", "q", "void_ratio", "z", "stress", "volume", "velocity", "displacement", "F"]
GRAIN_MEASURES = ["rve/fabric", "rve/z_mech", "rve/unbalanced", "rve/kinetic_energy"]
# points.xmf also shows the RVEs' grain measures where points and RVEs are one to one.
GRAIN_ARRAYS = ["fabric", "z_mech", "unbalanced", "kinetic_energy"]


def point_arrays(r, np):
    """The arrays points.xmf must show: the point fields, and the grain measures when every point
    has its own RVE in the same order (/rve/id equal to /points/id)."""
    one_to_one = "rve/id" in r and np.array_equal(r["rve/id"], r["points/id"])
    return sorted(POINT_ARRAYS + (GRAIN_ARRAYS if one_to_one else [])), one_to_one


CSV_COLUMNS = ["step", "time_s", "eps_ax", "eps_v", "p_mean_Pa", "q_mean_Pa"]


class Failure(Exception):
    pass


def expect(cond, what):
    if not cond:
        raise Failure(what)


def log(msg):
    print("check_outputs: " + msg, flush=True)


def check_results(path, h5py, np):
    """results.h5 with h5py; returns the arrays the other checks compare against."""
    with h5py.File(path, "r") as f:
        a = f.attrs
        expect(text(a["format"]) == "mpmxdem results", "results.h5: attribute format")
        expect(int(a["format_version"]) == 1, "results.h5: format_version")
        for key in ("software", "software_version", "conventions"):
            expect(key in a and text(a[key]), "results.h5: root attribute " + key)
        names = []
        f.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
        for n in names:
            ds = f[n]
            expect("unit" in ds.attrs and "description" in ds.attrs,
                   f"results.h5: /{n} lacks unit or description")
        nt = f["step"].shape[0]
        n_rve = f["rve/id"].shape[0]
        m = f["points/id"].shape[0]
        for n in names:
            if n in ("rve/id", "points/id"):
                continue
            shape = f[n].shape
            expect(shape[0] == nt, f"results.h5: /{n} has {shape[0]} rows, /step {nt}")
            if n.startswith("rve/"):
                expect(shape[1] == n_rve, f"results.h5: /{n} RVE axis {shape[1]} != {n_rve}")
            if n.startswith("points/"):
                expect(shape[1] == m, f"results.h5: /{n} point axis {shape[1]} != {m}")
        r = {k: f[k][()] for k in names}
    # Every point carries its RVE's p and q: find the RVE by value in the last row.
    if nt > 0:
        for q in ("p", "q"):
            rve_vals = set(r["rve/" + q][-1].tolist())
            expect(all(v in rve_vals for v in r["points/" + q][-1].tolist()),
                   f"results.h5: /points/{q} not among /rve/{q}")
    check_point_fields(r, np)
    check_grain_measures(r, np)
    log(f"results.h5 (h5py {h5py.__version__}): {nt} rows, {n_rve} RVEs, {m} points, "
        f"{len(names)} datasets with unit + description, format version 1")
    return r


def check_point_fields(r, np):
    """Point fields: velocity, displacement, F, volume, consistent with each other."""
    for k in ("points/velocity", "points/displacement", "points/F", "points/volume"):
        expect(k in r, f"results.h5: /{k} missing")
    nt = len(r["step"])
    if nt == 0:
        return
    x = r["points/x"]
    u = r["points/displacement"]
    if int(r["step"][0]) == 0:
        # x0 is the job's points = row 0's positions of a fresh run: the subtraction is exact.
        expect(np.array_equal(u, x - x[0]), "results.h5: /points/displacement != x - x(row 0)")
    F = r["points/F"].reshape(x.shape[:2] + (3, 3))
    V = r["points/volume"]
    if int(r["step"][0]) == 0 and np.all(np.isfinite(V)):
        # V = J V0 (J = det F); the two are updated step by step by different products, so they
        # agree to rounding: 1e-9 relative leaves 1e5 times the 1e-14 seen after 2000 steps.
        rel = np.abs(np.linalg.det(F) * V[0] / V - 1.0)
        expect(rel.max() < 1e-9, f"results.h5: volume != det(F) V0 (relative {rel.max():.3g})")
    expect(np.all(np.isfinite(r["points/velocity"])), "results.h5: /points/velocity not finite")


def check_grain_measures(r, np):
    """Per-RVE grain-scale measures: all NaN (continuum RVE) or physically sound."""
    for k in GRAIN_MEASURES:
        expect(k in r, f"results.h5: /{k} missing")
    fab = r["rve/fabric"]
    if fab.size == 0:
        return
    fab = fab.reshape(fab.shape[:2] + (3, 3))
    nan = np.isnan(r["rve/z_mech"])
    for k in GRAIN_MEASURES:
        v = r[k].reshape(r[k].shape[:2] + (-1,))
        expect(np.array_equal(np.isnan(v).all(axis=2), nan) and
               np.array_equal(np.isnan(v).any(axis=2), nan),
               f"results.h5: /{k} NaN where /rve/z_mech is not (or the reverse)")
    # A grain RVE (Z > 0) must have its measures; only continuum RVEs (Z = 0) report NaN.
    expect(not nan[r["rve/z"] > 0].any(), "results.h5: NaN grain measures of an RVE with Z > 0")
    ok = ~nan
    if not ok.any():
        return
    f = fab[ok]
    has = np.abs(f).sum(axis=(1, 2)) > 0  # an RVE without contacts has a zero fabric
    # <n n> of unit normals: trace 1 to rounding (a mean of thousands of terms: 1e-12).
    expect(np.all(np.abs(np.trace(f[has], axis1=1, axis2=2) - 1.0) < 1e-12),
           "results.h5: /rve/fabric trace != 1")
    expect(np.array_equal(f, np.swapaxes(f, 1, 2)), "results.h5: /rve/fabric not symmetric")
    z = r["rve/z"][ok]
    zm = r["rve/z_mech"][ok]
    # Removing a sphere with < 2 contacts cannot lower 2 Nc / N when it is >= 2.
    expect(np.all(zm[z >= 2.0] >= z[z >= 2.0] - 1e-12), "results.h5: /rve/z_mech < /rve/z")
    expect(np.all(r["rve/unbalanced"][ok] >= 0.0), "results.h5: /rve/unbalanced < 0")
    expect(np.all(r["rve/kinetic_energy"][ok] >= 0.0), "results.h5: /rve/kinetic_energy < 0")


def check_csv(path, r, np, use_pandas):
    nt = len(r["step"])
    if use_pandas:
        import pandas as pd

        # pandas' default float parser may be 1 ulp off the 17 digits; round_trip is exact.
        d = pd.read_csv(path, float_precision="round_trip")
        cols = list(d.columns)
        values = {c: d[c].to_numpy() for c in cols}
        client = "pandas " + pd.__version__
    else:
        with open(path, newline="") as fh:
            rows = list(csv.DictReader(fh))
        cols = list(rows[0].keys()) if rows else []
        values = {c: np.array([float(x[c]) for x in rows]) for c in cols}
        client = "csv.DictReader"
    expect(cols == CSV_COLUMNS, f"means.csv: columns {cols}, expected {CSV_COLUMNS}")
    g = np.genfromtxt(path, delimiter=",", names=True)
    expect(list(g.dtype.names) == CSV_COLUMNS, f"means.csv: numpy.genfromtxt names {g.dtype.names}")
    expect(len(values["step"]) == nt, f"means.csv: {len(values['step'])} rows, results.h5 {nt}")
    pairs = [("step", "step"), ("time_s", "time"), ("eps_ax", "means/eps_ax"),
             ("eps_v", "means/eps_v"), ("p_mean_Pa", "means/p"), ("q_mean_Pa", "means/q")]
    for c, ds in pairs:
        expect(np.array_equal(values[c].astype(float), r[ds].astype(float)),
               f"means.csv: column {c} differs from /{ds}")
    log(f"means.csv ({client}): header {','.join(cols)}, {nt} rows equal to results.h5; numpy.genfromtxt(names=True) takes the same header")


def paraview_child(xmf):
    """Runs in a child process: opens points.xmf with ParaView, prints what it read as JSON."""
    from paraview import servermanager as sm
    from paraview import simple
    from vtk.util.numpy_support import vtk_to_numpy

    reader = simple.OpenDataFile(xmf)
    times = list(reader.TimestepValues)
    out = {"reader": reader.GetXMLName(), "times": times, "steps": {}}
    picks = sorted({0, len(times) // 2, len(times) - 1}) if times else []
    for i in picks:
        reader.UpdatePipeline(times[i])
        data = sm.Fetch(reader)
        blocks = [data]
        if data.IsA("vtkMultiBlockDataSet"):
            blocks = [data.GetBlock(b) for b in range(data.GetNumberOfBlocks())]
        pts, arrays = [], {}
        for b in blocks:
            if b is None or b.GetNumberOfPoints() == 0:
                continue
            pts += vtk_to_numpy(b.GetPoints().GetData()).tolist()
            pd = b.GetPointData()
            for k in range(pd.GetNumberOfArrays()):
                arrays.setdefault(pd.GetArrayName(k), []).extend(
                    vtk_to_numpy(pd.GetArray(k)).tolist())
        out["steps"][str(i)] = {"points": pts, "arrays": arrays}
    print("PARAVIEW_JSON " + json.dumps(out))


def check_xmf_paraview(xmf, r, np):
    proc = subprocess.run(tool_command("check_outputs") + ["--paraview-child", xmf],
                          capture_output=True, text=True, timeout=600)
    line = [x for x in proc.stdout.splitlines() if x.startswith("PARAVIEW_JSON ")]
    expect(proc.returncode == 0 and line,
           f"points.xmf: ParaView failed ({proc.returncode}): {proc.stderr[-2000:]}")
    got = json.loads(line[0][len("PARAVIEW_JSON "):])
    nt = len(r["step"])
    expect(len(got["times"]) == nt, f"points.xmf: ParaView sees {len(got['times'])} time steps, "
           f"results.h5 has {nt} rows")
    expect(np.array_equal(np.array(got["times"]), r["time"]), "points.xmf: times != /time")
    m = r["points/id"].shape[0]
    for i, s in got["steps"].items():
        t = int(i)
        x = np.array(s["points"])
        expect(x.shape == (m, 3), f"points.xmf row {t}: ParaView shows {x.shape[0]} points, "
               f"results.h5 has {m}")
        expect(np.array_equal(x, r["points/x"][t]), f"points.xmf row {t}: positions != /points/x")
        names = sorted(s["arrays"])
        expected, one_to_one = point_arrays(r, np)
        expect(names == expected, f"points.xmf row {t}: arrays {names}, expected {expected}")
        expect(np.array_equal(np.array(s["arrays"]["id"]), r["points/id"]),
               f"points.xmf row {t}: id != /points/id")
        for a in POINT_VALUES:
            v = np.array(s["arrays"][a]).reshape(r["points/" + a][t].shape)
            expect(np.array_equal(v, r["points/" + a][t]), f"points.xmf row {t}: {a} differs")
        for a in GRAIN_ARRAYS if one_to_one else []:
            v = np.array(s["arrays"][a], dtype=float).reshape(r["rve/" + a][t].shape)
            expect(np.array_equal(v, r["rve/" + a][t], equal_nan=True),
                   f"points.xmf row {t}: {a} differs from /rve/{a}")
    log(f"points.xmf (ParaView, reader {got['reader']}): {nt} time steps at /time, rows "
        f"{sorted(int(i) for i in got['steps'])}: {m} points, arrays {','.join(expected)} "
        "equal to results.h5")


def check_xmf_text(xmf, r, np):
    import xml.etree.ElementTree as ET

    root = ET.parse(xmf).getroot()
    grids = root.findall("./Domain/Grid/Grid")
    nt = len(r["step"])
    expect(len(grids) == nt, f"points.xmf: {len(grids)} grids, results.h5 has {nt} rows")
    for t, g in enumerate(grids):
        expect(float(g.find("Time").get("Value")) == r["time"][t], f"points.xmf grid {t}: time")
        items = [g.find("Geometry/DataItem")] + [a.find("DataItem") for a in g.findall("Attribute")]
        names = sorted(a.get("Name") for a in g.findall("Attribute"))
        expected, _ = point_arrays(r, np)
        expect(names == expected, f"points.xmf grid {t}: attributes {names}, expected {expected}")
        for it in items:
            ref = it.text.strip()
            if "|" in ref:
                start = ref.split("|")[1].split(":")[0].split()
                expect(int(start[0]) == t, f"points.xmf grid {t}: {ref} selects row {start[0]}")
    log(f"points.xmf (ElementTree; ParaView not used): {nt} grids, row selections and "
        "times agree with results.h5")


def check_checkpoints(d, r, h5py):
    files = sorted(glob.glob(os.path.join(d, "checkpoint_*.h5")))
    for c in files:
        with h5py.File(c, "r") as f:
            expect(text(f.attrs["format"]) == "mpmxdem-farm-checkpoint", c + ": format")
            step = int(f.attrs["step"])
            expect(step in set(r["step"].tolist()), f"{c}: step {step} not a row of results.h5")
    log(f"checkpoints (h5py): {len(files)} opened, steps among results.h5's rows")


def check_jobs(d):
    import tomllib

    for name in ("job.toml", "job.resolved.toml"):
        with open(os.path.join(d, name), "rb") as fh:
            tomllib.load(fh)
    log("job.toml, job.resolved.toml (tomllib): parsed")


def check_run_summary(path, r):
    """run_summary.json (json): a run that reached its end time, its last row the last step."""
    with open(path) as fh:
        s = json.load(fh)
    expect(s["format"] == "mpmxdem run summary" and s["format_version"] == 1,
           "run_summary.json: format")
    expect(s["ended"] == "end_time" and s["exit_code"] == 0 and s["error"] == "",
           f"run_summary.json: ended {s['ended']}, exit_code {s['exit_code']}")
    expect(s["mpm_steps"] == int(r["step"][-1]) and s["time_s"] == float(r["time"][-1]),
           f"run_summary.json: step {s['mpm_steps']}, t {s['time_s']} against the last row's "
           f"{int(r['step'][-1])}, {float(r['time'][-1])}")
    expect(s["rve_steps"] > 0 and s["dem_steps"] >= 0 and s["wall_s"] > 0, "run_summary.json: work")
    log(f"run_summary.json (json): ended {s['ended']}, {s['mpm_steps']} MPM steps = the last row's, "
        f"{s['dem_steps']} DEM steps, wall {s['wall_s']:.2f} s")


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--paraview-child":
        paraview_child(sys.argv[2])
        return 0
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dir")
    ap.add_argument("--require", default="h5py", help="clients that must be present")
    ap.add_argument("--without", default="", help="clients not to use (pandas,paraview)")
    a = ap.parse_args()
    required = set(filter(None, a.require.split(",")))
    d = os.path.abspath(a.dir)

    def have(module):
        try:
            return importlib.util.find_spec(module) is not None
        except ImportError:
            return False

    # ParaView is only looked up here (its import is slow and bundles another HDF5).
    clients = {"h5py": have("h5py"), "pandas": have("pandas"), "paraview": have("paraview.simple")}
    for c in filter(None, a.without.split(",")):
        clients[c] = False
    missing = sorted(c for c in required if not clients.get(c, False))
    if missing:
        log("missing client(s): " + ", ".join(missing))
        return SKIP
    import h5py
    import numpy as np

    try:
        r = check_results(os.path.join(d, "results.h5"), h5py, np)
        check_csv(os.path.join(d, "means.csv"), r, np, clients["pandas"])
        if clients["paraview"]:
            check_xmf_paraview(os.path.join(d, "points.xmf"), r, np)
        else:
            check_xmf_text(os.path.join(d, "points.xmf"), r, np)
        check_checkpoints(d, r, h5py)
        check_jobs(d)
        check_run_summary(os.path.join(d, "run_summary.json"), r)
    except (Failure, KeyError, OSError) as e:
        log(f"FAILED: {type(e).__name__}: {e}")
        return 1
    log("all outputs of " + d + " passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
