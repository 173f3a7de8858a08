#!/usr/bin/python3
"""results.h5 can be read while a run writes it (issue 19.3): starts `mpiexec -n 2 mpmxdem run`,
opens results.h5 with h5py again and again while the run goes on, and checks that rows were read
before the run ended and that every row read live equals the finished file's row.

  read_live_run.py MPIEXEC EXE JOB DIR [MAX_STEPS]

Exit 77 (CTest skip) without h5py. Before the fix every open failed with errno 11 (EAGAIN: the
writer held HDF5's file lock).
"""

import os
import subprocess
import sys
import time

try:
    import h5py
    import numpy as np
except ImportError:
    print("read_live_run: h5py not installed: skipped")
    sys.exit(77)


def main():
    mpiexec, exe, job, out = sys.argv[1:5]
    steps = sys.argv[5] if len(sys.argv) > 5 else "2000"
    path = os.path.join(out, "results.h5")
    cmd = [mpiexec, "-n", "2", "--bind-to", "none", exe, "run", job, "--out", out, "--force",
           "--max-steps", steps]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            env=env)
    live = []  # (rows, step, q) of every successful read while the run was going on
    errors = []
    while proc.poll() is None:
        if os.path.exists(path):
            try:
                with h5py.File(path, "r") as f:
                    n = f["step"].shape[0]
                    if n > 0:
                        live.append((n, f["step"][:n], f["means/q"][:n]))
            except (OSError, KeyError) as e:
                errors.append(str(e))
        time.sleep(0.05)
    err = proc.stderr.read()
    if proc.returncode != 0:
        print(f"read_live_run: the run failed ({proc.returncode}):\n{err}")
        return 1
    with h5py.File(path, "r") as f:
        step = f["step"][()]
        q = f["means/q"][()]
    # Reads after the writer closed the file (mpiexec still finishing) prove nothing: only those
    # that found fewer rows than the finished file were made while the run was writing.
    running = [x for x in live if x[0] < len(step)]
    print(f"read_live_run: {len(running)} reads of rows while the run wrote results.h5 "
          f"(rows {sorted({x[0] for x in running})}), {len(errors)} failed opens")
    for e in errors[:3]:
        print("  failed open: " + e)
    if not running:
        print("read_live_run: FAILED: no row could be read while the run wrote results.h5")
        return 1
    for n, s, v in running:
        if not (np.array_equal(s, step[:n]) and np.array_equal(v, q[:n])):
            print(f"read_live_run: FAILED: rows 0..{n - 1} read live differ from the final file")
            return 1
    print(f"read_live_run: every row read live equals the finished file ({len(step)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
