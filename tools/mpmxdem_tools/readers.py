"""What a run directory of `mpmxdem run` holds, read one way for every tool: its jobs
(job.toml as given, job.resolved.toml with every default), its run summary (run_summary.json:
how it ended, its steps and wall time) and its results (results.h5, with h5py). The fields are the
program's own (docs/reference/outputs.md); no tool reads them from log text."""
import json
import os
import sys
import tomllib


def job(run, resolved=True):
    """The run's job as a dict: RUN/job.resolved.toml (every default filled in), or RUN/job.toml
    (the job as given) with resolved=False."""
    with open(os.path.join(run, "job.resolved.toml" if resolved else "job.toml"), "rb") as f:
        return tomllib.load(f)


def summary(run, required=True):
    """RUN/run_summary.json as a dict (keys: ended, exit_code, error, mpm_steps, time_s,
    end_time_s, wall_s, rve_steps, dem_steps, spared_rve_steps, ...); None where the run wrote none
    and required is False; exit naming the file where it is required."""
    path = os.path.join(run, "run_summary.json")
    if not os.path.exists(path):
        if required:
            sys.exit(f"{path}: missing (the run did not start, or is not an `mpmxdem run`)")
        return None
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def results(run):
    """RUN/results.h5 opened read-only with h5py (close it, or use it in a `with`)."""
    import h5py  # Debian package python3-h5py; only the tools that read results need it

    path = os.path.join(run, "results.h5")
    if not os.path.exists(path):
        sys.exit(f"{path}: missing (the run wrote no results yet?)")
    return h5py.File(path, "r")


def text_attribute(value):
    """An HDF5 string attribute as str (h5py gives bytes or str, by how it was written)."""
    return value.decode() if isinstance(value, bytes) else str(value)


def constraint_names(f):
    """The names of the rows of results.h5's constraints/ datasets, in order (the job's
    [[mpm.velocity]] / [[mpm.traction]] names)."""
    return text_attribute(f["constraints"].attrs["names"]).split(",")


def bench_figures(text):
    """The figures a DEM speed run prints, as a dict: bench_dem's lines ("spheres N threads T team
    M steps S wall W s cpu C s", "ms/step .. us/particle-step .. ...", "... hash H") and the same
    "us/particle-step" figure that tools/mpmxdem_tools/references/yade_triax_hertz_mindlin.py
    --bench-steps prints for YADE. Keys: us_per_particle_step (always), and where printed spheres,
    threads, steps, wall_s, cpu_s, hash. bench_dem's output is kept as text (not JSON) so that
    builds of any age can be compared in pairs; this is its one parser."""
    import re

    out = {}
    m = re.search(r"us/particle-step ([0-9.eE+-]+)", text)
    if not m:
        sys.exit("no 'us/particle-step' figure in the benchmark's output:\n" + text[-2000:])
    out["us_per_particle_step"] = float(m.group(1))
    m = re.search(r"^spheres (\d+) threads (\d+) team \d+ steps (\d+) wall ([0-9.eE+-]+) s "
                  r"cpu ([0-9.eE+-]+) s", text, re.M)
    if m:
        out.update(spheres=int(m.group(1)), threads=int(m.group(2)), steps=int(m.group(3)),
                   wall_s=float(m.group(4)), cpu_s=float(m.group(5)))
    m = re.search(r"hash ([0-9a-f]+)", text)
    if m:
        out["hash"] = m.group(1)
    return out
