#!/usr/bin/python3
"""Runs the jobs of jobs/ as their headers say, and compares each with its header: exit code and
wall time (a benchmark, not a test: run it before quoting a figure from a job).

  tools/mpmxdem-tools run_jobs [JOB.toml ...] [--build build] [--out /tmp/mpmxdem_jobs]
                                     [--factor 3] [--csv run_jobs.csv] [--dry-run]

Each job's header has a line `# Run:  <command>` (mpirun/mpiexec -n N ... mpmxdem run|dem JOB
--out DIR) and, for most, `# Wall time:  <T> s|min|h ...`. The command is run from the repository
root with `mpmxdem` replaced by BUILD/mpmxdem, `mpirun` by `mpiexec --bind-to none` (as root:
--allow-run-as-root) and --out by OUT/<job name>; a job still running after FACTOR times its
header's wall time (or 2 hours without one) is stopped and reported as such. Without JOB
arguments: every jobs/*.toml. The table gives, per job: exit code, wall time, the header's, their
ratio, and "ok" when the exit code is 0 and the ratio at most 2 (the promise a header makes), and
for a `run` job how it ended (its run_summary.json: the end time reached, or the numerical
failure's message).
--dry-run prints the commands and the header times only (every job must have a Run line: exit 1
otherwise).
"""
import argparse
import csv
import glob
import os
import re
import shlex
import subprocess
import sys
import time

from .. import readers
from ..paths import ROOT

UNITS = {"s": 1.0, "min": 60.0, "h": 3600.0}


def header(path):
    """(run command tokens or None, header wall time [s] or None) of a job file."""
    run, wall = None, None
    with open(path, encoding="utf-8") as f:
        for line in f:
            if not line.startswith("#"):
                break
            m = re.match(r"#\s*Run:\s*(.+)$", line)
            if m and run is None:
                run = shlex.split(m.group(1))
            m = re.match(r"#\s*Wall time:\s*([0-9.]+)\s*(s|min|h)\b", line)
            if m and wall is None:
                wall = float(m.group(1)) * UNITS[m.group(2)]
    return run, wall


def how_it_ended(out_dir):
    """How a `run` job ended, from its run_summary.json ("" for `dem` jobs, or none written)."""
    s = readers.summary(out_dir, required=False)
    if s is None:
        return ""
    if s["ended"] == "numerical_failure":
        return "numerical failure: " + s["error"].split("\n")[0][:160]
    return f"ended at {s['ended']}, t = {s['time_s']:.6g} s of {s['end_time_s']:.6g} s"


def command(tokens, build, out_dir):
    """The header's command made runnable here."""
    cmd = []
    k = 0
    while k < len(tokens):
        t = tokens[k]
        if t in ("mpirun", "mpiexec"):
            cmd += ["mpiexec", "--bind-to", "none"]
            if os.geteuid() == 0:
                cmd += ["--allow-run-as-root"]
        elif t == "--bind-to" and k + 1 < len(tokens):
            k += 1  # already given
        elif t == "mpmxdem" or t.endswith("/mpmxdem"):
            cmd.append(os.path.join(build, "mpmxdem"))
        elif t == "--out" and k + 1 < len(tokens):
            cmd += ["--out", out_dir]
            k += 1
        else:
            cmd.append(t)
        k += 1
    if "--out" not in cmd:
        cmd += ["--out", out_dir]
    return cmd + ["--force"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("jobs", nargs="*")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default="/tmp/mpmxdem_jobs")
    ap.add_argument("--factor", type=float, default=3.0)
    ap.add_argument("--csv", default="")
    ap.add_argument("--dry-run", action="store_true")
    args = ap.parse_args()
    jobs = args.jobs or sorted(glob.glob(os.path.join(ROOT, "jobs", "*.toml")))
    rows, missing = [], []
    for job in jobs:
        name = os.path.splitext(os.path.basename(job))[0]
        tokens, wall_h = header(job)
        if tokens is None:
            missing.append(job)
            print(f"{name}: no '# Run:' line in its header")
            continue
        cmd = command(tokens, args.build, os.path.join(args.out, name))
        if args.dry_run:
            print(f"{name}: header wall {wall_h if wall_h is not None else '-'} s: {shlex.join(cmd)}")
            continue
        limit = args.factor * wall_h if wall_h else 7200.0
        env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_rmaps_base_oversubscribe="1")
        t0 = time.monotonic()
        log = os.path.join(args.out, name + ".log")
        os.makedirs(args.out, exist_ok=True)
        with open(log, "w", encoding="utf-8") as lf:
            try:
                rc = subprocess.run(cmd, cwd=ROOT, stdout=lf, stderr=subprocess.STDOUT, env=env,
                                    timeout=limit, check=False).returncode
                status = ""
            except subprocess.TimeoutExpired:
                rc, status = -1, f"stopped after {limit:.0f} s"
        wall = time.monotonic() - t0
        ended = how_it_ended(os.path.join(args.out, name))
        if ended:
            status = (status + " " + ended).strip()
        ratio = wall / wall_h if wall_h else float("nan")
        ok = rc == 0 and (wall_h is None or ratio <= 2.0)
        rows.append({"job": name, "exit": rc, "wall_s": round(wall, 1),
                     "header_wall_s": wall_h if wall_h is not None else "",
                     "ratio": round(ratio, 2) if wall_h else "", "ok": "ok" if ok else "NO",
                     "note": status, "log": log})
        print(f"{name}: exit {rc}, {wall:.1f} s (header {wall_h if wall_h else '-'} s) "
              f"{'ok' if ok else 'NO'} {status}", flush=True)
    if rows:
        print("\n| job | exit | wall [s] | header [s] | ratio | ok |\n|---|---|---|---|---|---|")
        for r in rows:
            print(f"| {r['job']} | {r['exit']} | {r['wall_s']} | {r['header_wall_s']} | {r['ratio']} "
                  f"| {r['ok']} {r['note']} |")
        if args.csv:
            with open(args.csv, "w", newline="", encoding="utf-8") as f:
                w = csv.DictWriter(f, fieldnames=list(rows[0]))
                w.writeheader()
                w.writerows(rows)
    if missing:
        return 1
    return 0 if all(r["ok"] == "ok" for r in rows) else 2


if __name__ == "__main__":
    sys.exit(main())
