#!/usr/bin/python3
"""The energy balance of a strip-footing run, from its stored files: the footing's work (the
integral of its reaction over its settlement, reactions.csv) against the materials' internal work
and the kinetic energy (the run's progress lines in its log), and where the balance grows.

    created(t) = W_int(t) + E_kin(t) - W_footing(t)

W_footing leaves out the surcharge's work and the damping (a few per cent here), so a closed
balance stays at or a little below zero; a balance that rises by joules while the footing puts in
a fraction of that is energy from nothing, not the material's response (docs/design/mpm.md,
"Energy-growth guard"; docs/validation/footing.md, "The RVEs' footing"). Prints one line per
progress line kept (--every) and the largest rise of the balance: how much, over which
settlements, and the footing's work over the same settlements.

    tools/mpmxdem-tools footing_energy RUN LOG [--every N]
    tools/mpmxdem-tools footing_energy docs/data/footing_dem/dem_w0.2_h12.5 \\
        docs/data/footing_dem/dem_w0.2_h12.5.log
"""
import argparse
import bisect
import os
import re

import pandas as pd
from . import footing_curves

PROGRESS = re.compile(r"t = ([0-9.eE+-]+) s .*E_kin ([0-9.eE+-]+) J, W_int ([0-9.eE+-]+) J")


def footing_work(run):
    """[(time, s/B, q [Pa], W_footing [J])]: the footing's curve (footing_curves.curve, the
    staircase's boxes summed) and the trapezoid of its force over its settlement."""
    half, thick = footing_curves.footing_geometry(run)
    sb, q = footing_curves.curve(run)
    times = pd.read_csv(os.path.join(run, "reactions.csv"))["time_s"]
    out = []
    work = 0.0
    for k in range(len(sb)):
        if k > 0:  # force q half thick [N] over the settlement 2 half d(s/B) [m]
            work += 0.5 * (q[k] + q[k - 1]) * half * thick * 2 * half * (sb[k] - sb[k - 1])
        out.append((float(times[k]), float(sb[k]), float(q[k]), work))
    return out


def progress(log):
    """[(time, E_kin, W_int)] from the run's progress lines."""
    with open(log, encoding="utf-8", errors="replace") as f:
        return [tuple(float(x) for x in m.groups()) for m in map(PROGRESS.search, f) if m]


def balance(run, log):
    """[(time, s/B, q [Pa], W_footing, W_int, E_kin, created)] at the log's progress lines."""
    work = footing_work(run)
    times = [w[0] for w in work]
    rows = []
    for t, kin, wint in progress(log):
        k = min(bisect.bisect_left(times, t), len(work) - 1)
        _, sb, q, wf = work[k]
        rows.append((t, sb, q, wf, wint, kin, wint + kin - wf))
    return rows


def largest_rise(rows):
    """(rise [J], row where it starts, row where it ends): the largest increase of `created` from
    a row to a later one."""
    best = (0.0, 0, 0)
    low = 0
    for k, r in enumerate(rows):
        if r[6] < rows[low][6]:
            low = k
        if r[6] - rows[low][6] > best[0]:
            best = (r[6] - rows[low][6], low, k)
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", help="the run's folder (reactions.csv, job.resolved.toml)")
    ap.add_argument("log", help="the run's log (its progress lines)")
    ap.add_argument("--every", type=int, default=1, help="print every N-th progress line")
    a = ap.parse_args()
    rows = balance(a.run, a.log)
    if not rows:
        raise SystemExit("footing_energy: no progress lines with E_kin and W_int in %s" % a.log)
    print("%9s %7s %9s %11s %9s %9s %9s" % ("t [s]", "s/B", "q [MPa]", "W_footing", "W_int", "E_kin",
                                            "created"))
    for r in rows[:: max(1, a.every)]:
        print("%9.3f %7.3f %9.2f %11.3f %9.3f %9.3g %9.3f" % (r[0], r[1], r[2] / 1e6, r[3], r[4], r[5], r[6]))
    rise, i, j = largest_rise(rows)
    print("largest rise of the balance: %.3g J from s/B %.3f to %.3f (the footing's work over them "
          "%.3g J; at the end: created %.3g J of the footing's %.3g J)"
          % (rise, rows[i][1], rows[j][1], rows[j][3] - rows[i][3], rows[-1][6], rows[-1][3]))


if __name__ == "__main__":
    main()
