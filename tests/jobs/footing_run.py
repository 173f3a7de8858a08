"""What the footing tests share (tests/jobs/footing_limit_load.py, footing_associated.py,
footing_equilibrium.py): write a footing job with tools/mpmxdem_tools/jobs/footing_make_job.py, run it on 2 ranks,
and read its reactions.csv and load-settlement curve with the standard library (the staircase's
boxes summed, as tools/mpmxdem_tools/analysis/footing_curves.py does with pandas)."""
import csv
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
from mpmxdem_tools.jobs import footing_make_job  # noqa: E402


def run_rows(mpiexec, exe, out, params):
    """Runs the job of `params` (footing_make_job.job_text's arguments) into OUT/run on 2 ranks;
    returns the rows of its reactions.csv (dicts of strings)."""
    os.makedirs(out, exist_ok=True)
    job = os.path.join(out, "footing.toml")
    with open(job, "w") as f:
        f.write(footing_make_job.job_text(**params))
    run = os.path.join(out, "run")
    subprocess.run([mpiexec, "-n", "2", exe, "run", job, "--out", run, "--force"], check=True)
    with open(os.path.join(run, "reactions.csv")) as f:
        return list(csv.DictReader(f))


def run_curve(mpiexec, exe, out, params):
    """run_rows, read as (s / B, q [Pa], the footing's box names)."""
    rows = run_rows(mpiexec, exe, out, params)
    boxes = [c[:-len("_rz_N")] for c in rows[0] if re.fullmatch(r"footing(_\d+)?_rz_N", c)]
    half, thick = params["half_width"], params["cell"]
    sb = [-float(r["footing_uz_m"]) / (2 * half) for r in rows]
    q = [-sum(float(r[n + "_rz_N"]) for n in boxes) / (half * thick) for r in rows]
    return sb, q, boxes


def mean_over(sb, q, lo, hi):
    """The mean of q over s/B in [lo, hi]; exits naming the settlement reached if the run ended
    before hi."""
    if max(sb) < hi - 1e-3:
        sys.exit("the footing did not reach s/B = %g (%.3f)" % (hi, max(sb)))
    window = [qi for si, qi in zip(sb, q) if lo <= si <= hi + 1e-9]
    return sum(window) / len(window)
