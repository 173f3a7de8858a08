#!/usr/bin/python3
"""Families of plane-strain biaxial runs, one family per mesh: each draw's peak and band, and each
mesh's mean and range (docs/validation/biaxial.md, "Four meshes"). The same job drawn with other
samples (biaxial_make_jobs --seed K) differs in its peak and band as much as one mesh from the
next, so a mesh study compares the families' means and spreads, not single runs.

  tools/mpmxdem-tools biaxial_family RUN[:LABEL] [RUN ...] [--strains 0.03,0.041,0.05]
      [--csv OUT.csv] [--dem docs/data/biaxial_dem/dem_series_300_mean16.csv] [--figure FIG.png]
  tools/mpmxdem-tools biaxial_family --table CSV [--runs]

RUN: an `mpmxdem run` output directory of a biaxial job; runs are grouped by their mesh (cells
read from the job). Measured as `biaxial_analysis` measures them (the same functions): the first
peak of sigma_a / sigma_r and its axial strain; the single band's angle from the horizontal and
its thickness at the first output row at or past each strain of --strains (fitted away from the
platens); the ratio at 10 % where the run reaches it. Prints one row per run, then one row per
mesh (the number of draws, and for each figure its mean and range, min-max); --csv keeps the
runs' figures. --table prints the mesh rows (--runs: the run rows) from such a CSV, with the
standard library only (the tables of the manual are generated so). --figure: sigma_a / sigma_r
of every run (a colour per mesh, the pure DEM of --dem in black), and each draw's first peak and
band angles against the cell size.
"""
import argparse
import csv
import math
import statistics
import sys


def measures(r, strains):
    """Run r's figures (biaxial_analysis.Run): a flat dict, one CSV row."""
    import numpy as np

    from . import biaxial_analysis as B  # noqa: E402 (the tool beside this one)

    i = B.first_peak(r)
    row = {"run": r.label, "nx": r.cells[0], "nz": r.cells[1], "cell_mm": 1e3 * r.h,
           "peak": float(r.ratio[i]), "eps_peak": float(r.eps[i]),
           "ratio_10": float(np.interp(0.10, r.eps, r.ratio)) if r.eps[-1] >= 0.10 else math.nan}
    for s in strains:
        b = B.band_at(r, r.row_at(s)) if r.eps[-1] >= s - 1e-9 else None
        row[f"band_{s:g}"] = b["incl"] if b else math.nan
        row[f"width_mm_{s:g}"] = 1e3 * b["width"] if b else math.nan
    return row


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in r:
            if k != "run":
                r[k] = float(r[k]) if r[k] not in ("", "nan") else math.nan
    strains = [k[len("band_"):] for k in rows[0] if k.startswith("band_")] if rows else []
    return rows, strains


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


def spread(values, fmt):
    """'mean (min-max)' of the finite values; the value alone for one; '-' for none."""
    v = [x for x in values if not math.isnan(x)]
    if not v:
        return "-"
    if len(v) == 1:
        return fmt % v[0]
    return f"{fmt % statistics.fmean(v)} ({fmt % min(v)}-{fmt % max(v)})"


def widths_of(rows, strains):
    return [r[f"width_mm_{s}"] for r in rows for s in strains if not math.isnan(r[f"width_mm_{s}"])]


def run_table(rows, strains):
    heads = " | ".join(f"band at {100 * float(s):g} %" for s in strains)
    out = [f"| run | mesh | first peak of sigma_a / sigma_r | {heads} | thickness over these | ratio at 10 % |",
           "|---|---|---|" + "---|" * len(strains) + "---|---|"]
    for r in rows:
        bands = " | ".join("-" if math.isnan(r[f"band_{s}"]) else f"{r[f'band_{s}']:.1f}" for s in strains)
        w = widths_of([r], strains)
        w = f"{min(w):.1f}-{max(w):.1f} mm" if w else "-"
        r10 = "-" if math.isnan(r["ratio_10"]) else f"{r['ratio_10']:.2f}"
        out.append(f"| {r['run']} | {r['nx']:.0f} x {r['nz']:.0f} | {r['peak']:.2f} at "
                   f"{100 * r['eps_peak']:.1f} % | {bands} | {w} | {r10} |")
    return out


def family_table(rows, strains):
    heads = " | ".join(f"band at {100 * float(s):g} %" for s in strains)
    out = [f"| mesh (cell) | draws | first peak of sigma_a / sigma_r, mean (range) | {heads} | "
           "thickness (in cells) | ratio at 10 % |",
           "|---|---|---|" + "---|" * len(strains) + "---|---|"]
    meshes = sorted({(r["nx"], r["nz"]) for r in rows})
    for nx, nz in meshes:
        ms = [r for r in rows if (r["nx"], r["nz"]) == (nx, nz)]
        h = ms[0]["cell_mm"]
        cols = [spread([r["peak"] for r in ms], "%.2f")]
        cols += [spread([r[f"band_{s}"] for r in ms], "%.1f") for s in strains]
        w = widths_of(ms, strains)
        cols.append(f"{min(w):.1f}-{max(w):.1f} mm ({min(w) / h:.1f}-{max(w) / h:.1f})" if w else "-")
        cols.append(spread([r["ratio_10"] for r in ms], "%.2f"))
        out.append(f"| {nx:.0f} x {nz:.0f} ({h:.3g} mm) | {len(ms)} | " + " | ".join(cols) + " |")
    return out


def figure(runs, rows, strains, dem, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from . import biaxial_analysis as B  # noqa: E402

    meshes = sorted({(r["nx"], r["nz"]) for r in rows})
    colour = {c: plt.cm.viridis(k / max(1, len(meshes) - 1) * 0.9) for k, c in enumerate(meshes)}
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.3))
    if dem:
        s = B.dem_series(dem)
        ax[0].plot(100 * s["eps"], s["ratio"], "k-", lw=1.6, label="pure DEM")
    seen = set()
    for run, r in zip(runs, rows):
        c = (r["nx"], r["nz"])
        ax[0].plot(100 * run.eps, run.ratio, "-", color=colour[c], lw=0.9,
                   label=None if c in seen else f"{c[0]:.0f} x {c[1]:.0f}")
        seen.add(c)
    ax[0].set_xlabel("axial strain [%]")
    ax[0].set_ylabel("sigma_a / sigma_r [-]")
    ax[0].legend(fontsize=8)
    for c in meshes:
        ms = [r for r in rows if (r["nx"], r["nz"]) == c]
        h = ms[0]["cell_mm"]
        ax[1].plot([h] * len(ms), [r["peak"] for r in ms], "o", color=colour[c], mfc="none")
        ax[1].plot(h, np.mean([r["peak"] for r in ms]), "_", color="k", ms=14, mew=2)
        for k, (s, mk) in enumerate(zip(strains, "os^vD")):
            got = [r[f"band_{s}"] for r in ms if not math.isnan(r[f"band_{s}"])]
            hk = h * 1.06 ** (k - (len(strains) - 1) / 2)  # side by side on the log axis
            ax[2].plot([hk] * len(got), got, mk, color=colour[c], mfc="none",
                       label=f"at {100 * float(s):g} %" if c == meshes[0] else None)
            if got:
                ax[2].plot(hk, np.mean(got), "_", color="k", ms=10, mew=2)
    for a in ax[1:]:
        a.set_xscale("log")
        cells = sorted({r["cell_mm"] for r in rows})
        a.set_xticks(cells, [f"{h:.3g}" for h in cells])
        a.minorticks_off()
        a.set_xlabel("cell [mm] (finer to the right)")
        a.invert_xaxis()
    ax[1].set_ylabel("first peak of sigma_a / sigma_r (draws; bar: mean)")
    ax[2].set_ylabel("band angle from the horizontal [deg] (bar: mean)")
    ax[2].legend(fontsize=8, title="marker: axial strain")
    for a in ax:
        a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    print("wrote", path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("runs", nargs="*")
    ap.add_argument("--strains", default="0.03,0.041,0.05",
                    help="log axial strains at which the band is measured (comma-separated)")
    ap.add_argument("--csv", default=None, help="write the runs' figures to this CSV")
    ap.add_argument("--table", default=None, help="print the tables from this CSV (no run read)")
    ap.add_argument("--runs", dest="by_run", action="store_true", help="with --table: the run rows")
    ap.add_argument("--dem", default=None, help="a pure-DEM series (dem_series.csv) for the figure")
    ap.add_argument("--figure", default=None, help="write the figure to this PNG")
    a = ap.parse_args()
    if a.table:
        rows, strains = read_csv(a.table)
        print("\n".join(run_table(rows, strains) if a.by_run else family_table(rows, strains)))
        return 0
    if not a.runs:
        ap.error("give RUN directories, or --table CSV")
    from . import biaxial_analysis as B  # noqa: E402

    strains = [float(s) for s in a.strains.split(",")]
    runs, rows = [], []
    for spec in a.runs:
        path, _, label = spec.partition(":")
        runs.append(B.Run(path, label or None))
        rows.append(measures(runs[-1], strains))
    if a.csv:
        write_csv(a.csv, rows)
    # Print what the CSV holds (its rounding), so these tables are the ones `--table` generates.
    rows, keys = read_csv(a.csv) if a.csv else (rows, [f"{s:g}" for s in strains])
    print("\n".join(run_table(rows, keys)))
    print()
    print("\n".join(family_table(rows, keys)))
    if a.figure:
        figure(runs, rows, keys, a.dem, a.figure)
    return 0


if __name__ == "__main__":
    sys.exit(main())
