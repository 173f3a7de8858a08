#!/usr/bin/python3
"""Load-settlement curves of strip-footing runs (jobs/footing_plane_strain.toml,
tools/mpmxdem_tools/jobs/footing_make_job.py): the bearing pressure q = -footing_rz / (half-width x thickness)
against the settlement s / B, from each run's reactions.csv (pandas), the half-width and the
thickness read from the run's resolved job. Prints q at a few settlements per run; with --out, a
figure of every run's curve.

    tools/mpmxdem-tools footing_curves RUN [RUN ...] [--label NAME ...] [--out curves.png]
        [--theory LABEL=PHI_DEG ...] [--q0 50e3]   (horizontal lines at Prandtl's q0 N_q(phi),
                                                     tools/mpmxdem_tools/analysis/bearing_capacity.py)
        [--compliance]   (also the secant compliance d(s/B)/dq [1/MPa] over intervals of s/B, and
                          its change from each run to the next: how a layer's size softens it)
"""
import argparse
import os
import re

import pandas as pd
from .. import readers


def footing_geometry(run):
    """(half-width, thickness) [m] of the run's footing: the footing box's upper x, the grid's
    y spacing (plane strain: one cell through y)."""
    job = readers.job(run)
    box = [v for v in job["mpm"]["velocity"] if v.get("name") == "footing"][0]
    return box["max"][0], job["mpm"]["grid"]["spacing"][1]


def curve(run):
    """(s / B, q [Pa]) of a run. A footing deeper than half a cell is a staircase of boxes
    (footing, footing_1, ...; tools/mpmxdem_tools/jobs/footing_make_job.py): its reaction is their sum, its
    settlement that of the first box (held from the start)."""
    half, thick = footing_geometry(run)
    r = pd.read_csv(os.path.join(run, "reactions.csv"))
    boxes = [c for c in r.columns if re.fullmatch(r"footing(_\d+)?_rz_N", c)]
    return -r["footing_uz_m"] / (2 * half), -r[boxes].sum(axis=1) / (half * thick)


COMPLIANCE_INTERVALS = ((0.0, 0.01), (0.01, 0.02), (0.02, 0.05), (0.05, 0.1))


def compliance(sb, q, lo, hi):
    """Secant d(s/B)/dq [1/MPa] between the rows nearest s/B = lo and hi (None where the run
    has no row within 0.005 of either)."""
    a, b = (sb - lo).abs().idxmin(), (sb - hi).abs().idxmin()
    if abs(sb[a] - lo) > 0.005 or abs(sb[b] - hi) > 0.005 or q[b] == q[a]:
        return None
    return float(sb[b] - sb[a]) / float((q[b] - q[a]) / 1e6)


def print_compliance(labels, curves):
    print("secant compliance d(s/B)/dq [1/MPa] over s/B " +
          ", ".join("%g-%g" % iv for iv in COMPLIANCE_INTERVALS) + " (change from the run above)")
    before = None
    for lab, (sb, q) in zip(labels, curves):
        vals = [compliance(sb, q, lo, hi) for lo, hi in COMPLIANCE_INTERVALS]
        cells = []
        for k, v in enumerate(vals):
            prev = before[k] if before else None
            cells.append("%8s" % "-" if v is None else
                         "%.4f" % v + (" (%+.4f)" % (v - prev) if prev is not None else " " * 10))
        print("%-40s " % lab + "  ".join(cells))
        before = vals


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--label", action="append", default=[])
    ap.add_argument("--out")
    ap.add_argument("--theory", action="append", default=[], metavar="LABEL=PHI_DEG",
                    help="a line at q0 N_q(phi) on the figure")
    ap.add_argument("--q0", type=float, default=50e3, help="surcharge [Pa] of the theory lines")
    ap.add_argument("--title")
    ap.add_argument("--compliance", action="store_true",
                    help="print the secant compliance d(s/B)/dq over intervals of s/B")
    a = ap.parse_args()
    labels = a.label + [os.path.basename(r.rstrip("/")) for r in a.runs[len(a.label):]]
    curves = [curve(r) for r in a.runs]
    marks = (0.02, 0.05, 0.1, 0.2, 0.3, 0.4)
    print("%-40s " % "run" + " ".join("q(s/B=%g) [MPa]" % m for m in marks))
    for lab, (sb, q) in zip(labels, curves):
        vals = []
        for m in marks:
            k = (sb - m).abs().idxmin()
            vals.append("%15.3f" % (q[k] / 1e6) if abs(sb[k] - m) < 0.005 else "%15s" % "-")
        print("%-40s " % lab + " ".join(vals))
    if a.compliance:
        print_compliance(labels, curves)
    if a.out:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(9.5, 4.2))
        for lab, (sb, q) in zip(labels, curves):
            ax.plot(sb, q / 1e6, lw=1, label=lab)
        from . import bearing_capacity
        for k, t in enumerate(a.theory):
            label, phi = t.rsplit("=", 1)
            qu = a.q0 * bearing_capacity.n_q(float(phi)) / 1e6
            ax.axhline(qu, color="k", lw=0.8, ls=("--", ":", "-.")[k % 3],
                       label="%s: q0 N_q(%s deg) = %.2f MPa" % (label, phi, qu))
        if a.title:
            ax.set_title(a.title, fontsize=9)
        ax.set_xlabel("settlement s / B")
        ax.set_ylabel("bearing pressure q [MPa]")
        ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(a.out, dpi=120)


if __name__ == "__main__":
    main()
