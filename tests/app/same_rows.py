"""results.h5 of a run stopped and continued (by a signal, --max-wall or Slurm) against a straight
run's: every dataset byte for byte, once the rows the stopped run wrote at the steps it stopped at
are left out (a stop writes the row of its step: docs/reference/errors.md, "Stopping a run").
h5diff cannot say so: it exits 0 on series of different lengths ("not comparable").
Usage: same_rows.py STRAIGHT.h5 STOPPED.h5 [STOP_STEP...]"""
import sys

import h5py
import numpy as np


def datasets(f):
    names = []
    f.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
    return sorted(names)


a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
assert datasets(a) == datasets(b), "not the same datasets"
steps = b["step"][()]
extra = np.isin(steps, [int(s) for s in sys.argv[3:]]) & ~np.isin(steps, a["step"][()])
for n in datasets(a):
    x, y = a[n][()], b[n][()]
    if b[n].maxshape[0] is None:  # a time series: one row per output step
        y = y[~extra]
    assert x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes(), n
print(f"results.h5: {len(datasets(a))} datasets, {len(a['step'])} rows identical to the straight"
      f" run's (the {extra.sum()} rows written at the stops left out)")
