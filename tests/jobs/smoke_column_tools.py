"""Smoke run of the column analysis tools on a real run of tests/jobs/column_collapse_tiny.toml:
tools/mpmxdem-tools mpm_column_collapse writes its CSVs and figures, tools/mpmxdem-tools column_grain_scale --analyse
keeps them with the RVEs' series (tools/mpmxdem_tools/analysis/column_inertial_numbers.py and tools/mpmxdem_tools/analysis/column_cell_stress.py
beside it), and its time axis starts at the gate's release (the job's
`until`, 0.01 s): the end time it reports is the run's less the gate's hold.

Usage: smoke_column_tools.py RUN_DIR. Exit 77 (skipped) without h5py, numpy, pandas or matplotlib.
"""
import csv
import os
import shutil
import subprocess
import sys
import tempfile

for module in ("h5py", "numpy", "pandas", "matplotlib"):
    try:
        __import__(module)
    except ImportError:
        print(f"SKIPPED: {module} missing")
        sys.exit(77)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
from mpmxdem_tools.analysis import column_grain_scale as cgs  # noqa: E402

run = os.path.abspath(sys.argv[1])
with tempfile.TemporaryDirectory() as tmp:
    subprocess.run([sys.executable, os.path.join(ROOT, "tools", "mpmxdem-tools"), "mpm_column_collapse", run,
                    "--data", tmp, "--fig", tmp], check=True, cwd=ROOT, stdout=subprocess.DEVNULL)
    for name in ("column_mpm_front.png", "column_mpm_profiles.png", "column_mpm_inertial.png",
                 "summary.csv"):
        assert os.path.exists(os.path.join(tmp, name)), name
    data = os.path.join(tmp, "grain_scale")
    subprocess.run([sys.executable, os.path.join(ROOT, "tools", "mpmxdem-tools"), "column_grain_scale",
                    "--analyse", run, "tiny", "--data", data], check=True, cwd=ROOT,
                   stdout=subprocess.DEVNULL)
    for kind in ("timeseries", "profiles", "summary", "mobilised", "core"):
        assert os.path.exists(os.path.join(data, f"tiny_{kind}.csv")), kind
    shutil.copy(os.path.join(run, "job.toml"), os.path.join(data, "tiny.toml"))
    summary = list(csv.DictReader(open(os.path.join(data, "tiny_summary.csv"))))[0]
    assert int(summary["rves"]) == 32, summary["rves"]
    tstar = float(summary["tstar_s"])
    release = cgs.gate_release(os.path.join(data, "tiny.toml"))
    assert release == 0.01, release
    r = cgs.rows(data, os.path.join(ROOT, "docs", "data", "column_collapse_yade"), [(2, "tiny", "")])
    want = float(summary["t_end_over_tstar"]) - 0.01 / tstar
    assert abs(r[(2, "tiny")]["t_end"] - want) < 1e-3, (r[(2, "tiny")]["t_end"], want)
    # The inertial numbers of the same run: every point counted once per row in one regime.
    subprocess.run([sys.executable, os.path.join(ROOT, "tools", "mpmxdem-tools"), "column_inertial_numbers",
                    "--analyse", run, "tiny", "--data", data], check=True, cwd=ROOT,
                   stdout=subprocess.DEVNULL)
    inertial = list(csv.DictReader(open(os.path.join(data, "tiny_inertial.csv"))))
    assert len(inertial) > 2, len(inertial)
    for row in inertial:
        regimes = sum(int(row[k]) for k in ("rves_material_rate", "rves_quasi_static", "rves_held"))
        assert regimes == int(row["points"]) == 32, row
    # (The tiny column, 2500 d50 long, flows at I_m below 1e-3 over this short run: its RVEs stay
    # quasi-static; the grain-scale columns of docs/validation reach 0.1-1.)
    # Where an RVE ran at the material's rate (guard bit 5) the material was faster than I_n in
    # that step; the rate over the output interval (I_m) is a mean, so only its median is checked.
    points = list(csv.DictReader(open(os.path.join(data, "tiny_inertial_points.csv"))))
    fast = sorted(float(p["i_m"]) for p in points if p["i_rve"] and int(p["guards"]) & 32)
    if fast:
        assert fast[len(fast) // 2] > float(points[0]["i_n"]), fast
    # How the points of a cell share its pressure: shares between 1/n and 1, one row per output.
    subprocess.run([sys.executable, os.path.join(ROOT, "tools", "mpmxdem-tools"), "column_cell_stress",
                    "--analyse", run, "tiny", "--data", data], check=True, cwd=ROOT,
                   stdout=subprocess.DEVNULL)
    cells = list(csv.DictReader(open(os.path.join(data, "tiny_cells.csv"))))
    assert len(cells) == len(inertial) + 1, (len(cells), len(inertial))
    for row in cells:
        if int(row["loaded_cells"]):
            assert 0.0 < float(row["share_median"]) <= 1.0, row
            assert 0.0 <= float(row["free_fraction"]) < 1.0, row
    print(f"column tools: ok (32 RVEs; released at 0.01 s = {0.01 / tstar:.3f} t*, the run ends "
          f"{r[(2, 'tiny')]['t_end']:.3f} t* after it)")
