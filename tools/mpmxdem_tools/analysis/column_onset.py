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
  --back ITEM...   one row per ITEM (as --table) on what stands at the back wall at the end: H_f / H0
                   (the top of the bin at the wall), the width from the wall over which the deposit
                   stands at 0.95 H0 or more (in L0 and, for MPM x DEM, in spacings of its points),
                   the mean height over x < L0/4 (the mass kept at the back) and the height at L0/4
  --self-test      checks the first-crossing time on a synthetic series and the standing width on
                   a synthetic profile

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


def locate(item, data, yade):
    """(stem, label, whether it is an MPM x DEM run, its folder) of an ITEM, STEM or STEM=LABEL."""
    stem, _, label = item.partition("=")
    mpm = os.path.exists(os.path.join(data, f"{stem}_timeseries.csv"))
    return stem, label, mpm, data if mpm else yade


def series(item, data, yade):
    """(label, times, kinetic energies, fronts at 1/2/3 t* and the end, H_f / H0) of one item."""
    stem, label, mpm, folder = locate(item, data, yade)
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


def standing_width(xs, hs, level):
    """How far from the wall (x = 0) the profile (centres xs of equal bins, heights hs) stays at
    level or above: the outer edge of the last such bin of the run that starts at the wall (0 if
    none)."""
    half = (xs[1] - xs[0]) / 2 if len(xs) > 1 else xs[0]
    width = 0.0
    for x, h in zip(xs, hs):
        if h < level:
            break
        width = x + half
    return width


def back(item, data, yade):
    """(label, H_f / H0, standing width / L0, the same in point spacings or None, mean h / H0 over
    x < L0/4, h / H0 at L0/4) of one item."""
    stem, label, mpm, folder = locate(item, data, yade)
    s = cgs.read_csv(os.path.join(folder, f"{stem}_summary.csv"))[0]
    L0, H0 = float(s["L0_m"]), float(s["H0_m"])
    xs, hs = cgs.final_profile(os.path.join(folder, f"{stem}_profiles.csv"))
    width = standing_width(xs, hs, 0.95 * H0)
    spacings = width / float(s["cell_m"]) if mpm else None
    return (label or stem, float(s["Hf_over_H0"]), width / L0, spacings,
            cgs.back_mass_height((xs, hs), L0, H0), cgs.interp(L0 / 4, xs, hs) / H0)


def back_table(items, data, yade):
    lines = ["| column | H_f/H0 | standing at >= 0.95 H0 from the wall: width / L0 (point spacings) "
             "| mean h/H0 over x < L0/4 | h/H0 at L0/4 |", "|---|---|---|---|---|"]
    for item in items:
        label, hf, width, spacings, mean, quarter = back(item, data, yade)
        in_spacings = "" if spacings is None else f" ({spacings:.1f})"
        lines.append(f"| {label} | {hf:.2f} | {width:.3f}{in_spacings} | {mean:.2f} | {quarter:.2f} |")
    return "\n".join(lines)


def self_test():
    """A kinetic energy growing as t^2 / 100 reaches 0.01 at t = 1; one that stays below never does."""
    ts = [0.1 * i for i in range(40)]
    got = first_reaching(ts, [t * t / 100.0 for t in ts], KE_LEVEL)
    assert got is not None and abs(got - 1.0) < 0.01, got
    assert first_reaching(ts, [1e-4] * len(ts), KE_LEVEL) is None
    xs = [0.5 + k for k in range(10)]  # bins of width 1 from the wall
    assert standing_width(xs, [1.0, 1.0, 0.97, 0.5] + [1.0] * 6, 0.95) == 3.0  # the run at the wall only
    assert standing_width(xs, [0.9] + [1.0] * 9, 0.95) == 0.0
    print("column_onset self-test: ok")


def main():
    ap = argparse.ArgumentParser(prog="mpmxdem-tools column_onset", description=__doc__.split("\n")[0])
    ap.add_argument("--data", default=os.path.join(ROOT, "docs", "data", "column_collapse_mpm_grain_scale"))
    ap.add_argument("--yade", default=os.path.join(ROOT, "docs", "data", "column_collapse_yade"))
    ap.add_argument("--table", nargs="+", metavar="ITEM")
    ap.add_argument("--back", nargs="+", metavar="ITEM")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    if args.self_test:
        self_test()
    elif args.table:
        print(table(args.table, args.data, args.yade))
    elif args.back:
        print(back_table(args.back, args.data, args.yade))
    else:
        ap.print_usage()
        sys.exit(2)


if __name__ == "__main__":
    main()
