#!/usr/bin/python3
"""How soon a column starts to flow: its kinetic energy after the release, beside its fronts and deposit.

docs/validation/column_collapse.md ("The RVEs' packing"). A column that starts late reaches the
grains' deposit late or not at all; how late is read from the kinetic energy of the motion
(M g H0 units) at 0.5, 1 and 2 t* after the release, and from the first time it reaches
0.01 M g H0 (about half the grains' at 1 t* at a = 1), beside the front to 0.05 H0 at 1, 2 and 3 t*,
the runout (the same front at the end) and the top at the back wall, H_f / H0.

Modes:
  --table ITEM...  one row per ITEM, STEM or STEM=LABEL: an MPM x DEM stem with DATA/STEM_timeseries.csv
                   (kinetic_motion_over_MgH0, times counted from the gate's release),
                   DATA/STEM_summary.csv, DATA/STEM_profiles.csv (the runout, from its final rows)
                   and DATA/STEM_fronts05.csv (column_fronts --analyse; a run kept before that tool
                   has none: its fronts during the flow are shown as -), or a
                   YADE tag with YADE/TAG_timeseries.csv, _summary.csv and _profiles.csv
  --self-test      checks the first-crossing time on a synthetic series

Usage: tools/mpmxdem-tools column_onset [--data D] [--yade Y] MODE. Defaults: D =
docs/data/column_collapse_mpm_grain_scale, Y = docs/data/column_collapse_yade. Standard library only.
"""
import argparse
import math
import os
import sys

from . import column_fronts
from . import column_grain_scale as cgs
from ..paths import ROOT

KE_TIMES = (0.5, 1.0, 2.0)
KE_LEVEL = 0.01  # M g H0


def first_reaching(ts, ks, level):
    """The first time (linear between samples) at which ks reaches level; None if it never does."""
    for i, k in enumerate(ks):
        if k >= level:
            if i == 0:
                return ts[0]
            return ts[i - 1] + (level - ks[i - 1]) * (ts[i] - ts[i - 1]) / (k - ks[i - 1])
    return None


def number(value):
    """A front to two decimals; an unmeasured one (nan) as a dash."""
    return "-" if math.isnan(value) else f"{value:.2f}"


def series(item, data, yade):
    """(label, times, kinetic energies, fronts at 1/2/3 t* and the end, H_f / H0) of one item."""
    stem, _, label = item.partition("=")
    mpm = os.path.exists(os.path.join(data, f"{stem}_timeseries.csv"))
    folder = data if mpm else yade
    rows = cgs.read_csv(os.path.join(folder, f"{stem}_timeseries.csv"))
    hf = float(cgs.read_csv(os.path.join(folder, f"{stem}_summary.csv"))[0]["Hf_over_H0"])
    fronts = column_fronts.profile_fronts(folder, stem)
    if not mpm:
        return (label or f"pure DEM (YADE) {stem}", [float(r["t_over_tstar"]) for r in rows],
                [float(r["kinetic_over_MgH0"]) for r in rows], fronts, hf)
    fronts_csv = os.path.join(data, f"{stem}_fronts05.csv")  # runs kept before the tool: none
    if os.path.exists(fronts_csv):  # the profiles of a run hold its final rows only
        by = {r["t_label"]: float(r["front05_over_L0"]) for r in cgs.read_csv(fronts_csv)}
        fronts[:3] = [by[t] for t in column_fronts.TIMES[:3]]
    return (label or f"MPM x DEM {stem}", cgs.released_times(data, stem, rows),
            [float(r["kinetic_motion_over_MgH0"]) for r in rows], fronts, hf)


def table(items, data, yade):
    lines = ["| column | kinetic energy / (M g H0) at " + " / ".join(f"{t:g}" for t in KE_TIMES)
             + f" t* | reaches {KE_LEVEL:g} M g H0 at (t*) | front to 0.05 H0 at 1 / 2 / 3 t* | runout | H_f/H0 |",
             "|---|---|---|---|---|---|"]
    for item in items:
        label, ts, ks, fronts, hf = series(item, data, yade)
        first = first_reaching(ts, ks, KE_LEVEL)
        lines.append(f"| {label} | " + " / ".join(f"{cgs.interp(t, ts, ks):.4f}" for t in KE_TIMES)
                     + f" | {'never' if first is None else f'{first:.2f}'} | "
                     + " / ".join(number(f) for f in fronts[:3]) + f" | {number(fronts[3])} | {hf:.2f} |")
    return "\n".join(lines)


def self_test():
    """A kinetic energy growing as t^2 / 100 reaches 0.01 at t = 1; one that stays below never does."""
    ts = [0.1 * i for i in range(40)]
    got = first_reaching(ts, [t * t / 100.0 for t in ts], KE_LEVEL)
    assert got is not None and abs(got - 1.0) < 0.01, got
    assert first_reaching(ts, [1e-4] * len(ts), KE_LEVEL) is None
    print("column_onset self-test: ok")


def main():
    ap = argparse.ArgumentParser(prog="mpmxdem-tools column_onset", description=__doc__.split("\n")[0])
    ap.add_argument("--data", default=os.path.join(ROOT, "docs", "data", "column_collapse_mpm_grain_scale"))
    ap.add_argument("--yade", default=os.path.join(ROOT, "docs", "data", "column_collapse_yade"))
    ap.add_argument("--table", nargs="+", metavar="ITEM")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    if args.self_test:
        self_test()
    elif args.table:
        print(table(args.table, args.data, args.yade))
    else:
        ap.print_usage()
        sys.exit(2)


if __name__ == "__main__":
    main()
