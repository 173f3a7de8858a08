#!/usr/bin/python3
"""How far apart the biaxial runs of a mesh study are, field by field: each run's accumulated deviatoric strain at one axial strain, averaged over common bins of the undeformed specimen, and the relative RMS difference between successive meshes.

A band that is set by the mesh moves and thins from mesh to mesh, so the difference between two
successive meshes stays large; a field that converges (a material length resolved by the cells)
differs less and less. The fields are compared in the material frame: each point is binned by its
position in the first output row (the undeformed specimen), so the bins are the same material on
every mesh. Bins: the coarsest run's cells (each then holds whole cells' points of every finer
mesh). Volume-weighted means per bin; the difference of runs a and b is sqrt(sum_bins (a - b)^2
/ sum_bins b^2), b the finer.

    tools/mpmxdem-tools biaxial_field_convergence RUN_16x32 RUN_32x64 RUN_64x128 [--at-strain 0.105]
    tools/mpmxdem-tools biaxial_field_convergence --maps FIG.png RUN[:LABEL] ... [--at-strain 0.105]
    tools/mpmxdem-tools biaxial_field_convergence --self-test

The table gives per run also A50, the share of the specimen's volume that carries half of its
accumulated deviatoric strain (a width measure that needs no band fit: it suits a diffuse X).
--maps draws, instead of the table, one panel per run: its points in the deformed specimen
coloured by the accumulated deviatoric strain at the axial strain (one colour scale for all, to
the 99th percentile of every run's), the label (default: the run's directory name) as title.

Needs python3-numpy, and python3-h5py to read runs (Debian); reads them with tools/mpmxdem_tools/analysis/biaxial_analysis.py.
"""
import argparse
import sys

try:
    import numpy as np
except ImportError:  # --help works without it; the self-test exits 77 (skipped by the suite)
    np = None


def binned(x0, value, volume, lo, size, shape):
    """Volume-weighted mean of value over the bins of the (x, z) plane (NaN where a bin is empty)."""
    i = np.clip(((x0[:, 0] - lo[0]) / size[0]).astype(int), 0, shape[0] - 1)
    k = np.clip(((x0[:, 2] - lo[1]) / size[1]).astype(int), 0, shape[1] - 1)
    num = np.zeros(shape)
    den = np.zeros(shape)
    np.add.at(num, (i, k), volume * value)
    np.add.at(den, (i, k), volume)
    with np.errstate(invalid="ignore"):
        return num / den


def relative_difference(a, b):
    """sqrt(sum (a - b)^2 / sum b^2) over the bins both fill."""
    both = np.isfinite(a) & np.isfinite(b)
    return float(np.sqrt(((a - b)[both] ** 2).sum() / (b[both] ** 2).sum()))


def read_run(path, at_strain, label=None):
    """A run as tools/mpmxdem_tools/analysis/biaxial_analysis.py reads it, at the first row past the axial strain."""
    from .biaxial_analysis import Run  # the biaxial's reader (needs h5py), beside this tool
    r = Run(path, label)
    row = r.row_at(at_strain)
    return {"label": r.label, "x0": r.x[0], "x": r.x[row], "eps_dev": r.eps_dev(row),
            "volume": r.f["points/volume"][row], "h": (r.h, r.H / r.cells[1]),
            "lo": r.lo,
            "size": (r.W, r.H), "eps": float(r.eps[row])}


def a50(run):
    """The share of the specimen's volume that carries half of its accumulated deviatoric strain
    (the points with the largest strain first): about w L / (2 A) for a band of thickness w and
    length L in a specimen of area A; 0.5 for a uniform field."""
    e, v = run["eps_dev"], run["volume"]
    order = np.argsort(-e, kind="stable")
    carried = np.cumsum((e * v)[order]) / float((e * v).sum())
    n = int(np.searchsorted(carried, 0.5)) + 1
    return float(v[order][:n].sum() / v.sum())


def compare(runs):
    """Rows (a, b, difference) for successive runs, binned on the coarsest run's cells."""
    coarse = max(runs, key=lambda r: r["h"][0])
    size = coarse["h"]
    shape = (int(round(coarse["size"][0] / size[0])), int(round(coarse["size"][1] / size[1])))
    fields = [binned(r["x0"], r["eps_dev"], r["volume"], coarse["lo"], size, shape) for r in runs]
    rows = []
    for a in range(len(runs) - 1):
        rows.append((runs[a]["label"], runs[a + 1]["label"],
                     relative_difference(fields[a], fields[a + 1])))
    return rows, fields


def draw_maps(runs, out):
    """One panel per run: the points where they are, coloured by eps_dev, one colour scale."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    top = max(float(np.percentile(r["eps_dev"], 99)) for r in runs)
    fig, axs = plt.subplots(1, len(runs), figsize=(2.5 * len(runs) + 1.0, 4.4), squeeze=False,
                            layout="constrained")
    for ax, r in zip(axs[0], runs):
        x = 1e3 * r["x"][:, 0]
        z = 1e3 * r["x"][:, 2]
        ax.set_xlim(x.min() - 2.0, x.max() + 2.0)
        ax.set_ylim(z.min() - 2.0, z.max() + 2.0)
        ax.set_aspect("equal")
        fig.canvas.draw()  # the axes' final size: one square marker per point spacing
        pts_per_mm = (ax.transData.transform((1.0, 0.0)) - ax.transData.transform((0.0, 0.0)))[0] \
            * 72.0 / fig.dpi
        side = 1.4 * 0.5e3 * r["h"][0] * pts_per_mm  # 2 points per cell, overlapping where they spread
        sc = ax.scatter(x, z, c=r["eps_dev"], s=side ** 2, marker="s", cmap="viridis", vmin=0.0,
                        vmax=top, linewidths=0)
        ax.set_xlabel("x [mm]")
        ax.set_title(f"{r['label']}\neps_a {100 * r['eps']:.1f} %", fontsize=8)
    axs[0][0].set_ylabel("z [mm]")
    fig.colorbar(sc, ax=axs[0].tolist(), label="accumulated deviatoric strain", shrink=0.8)
    fig.savefig(out, dpi=110)
    print("wrote", out)


def self_test():
    """A band of fixed width converges, a band one cell wide on every mesh does not."""
    rng = np.random.default_rng(1)

    def run(cells, width_of):
        h = 0.05 / cells
        xs = (np.arange(2 * cells) + 0.5) * 0.5 * h
        zs = (np.arange(4 * cells) + 0.5) * 0.5 * h
        X, Z = np.meshgrid(xs, zs, indexing="ij")
        x0 = np.stack([X.ravel(), np.zeros(X.size), Z.ravel()], axis=1)
        d = np.abs((Z.ravel() - 0.05) - (X.ravel() - 0.025)) / np.sqrt(2.0)
        w = width_of(h)
        value = np.exp(-0.5 * (d / w) ** 2) * 0.2 * 0.005 / w + 1e-3 * rng.random(d.size)
        return {"label": f"{cells}", "x0": x0, "eps_dev": value, "volume": np.full(d.size, h * h),
                "h": (h, h), "lo": (0.0, 0.0), "size": (0.05, 0.1), "eps": 0.1}

    fixed = [run(c, lambda h: 0.004) for c in (16, 32, 64)]
    mesh = [run(c, lambda h: 1.0 * h) for c in (16, 32, 64)]
    df = [r[2] for r in compare(fixed)[0]]
    dm = [r[2] for r in compare(mesh)[0]]
    assert df[1] < df[0] and df[1] < 0.05, df
    assert dm[1] > 0.3 and dm[0] > 0.3, dm
    uniform = dict(fixed[0], eps_dev=np.ones(fixed[0]["eps_dev"].size))
    assert abs(a50(uniform) - 0.5) < 0.01, a50(uniform)
    band = a50(mesh[2])  # a band one cell (0.78 mm) wide, 0.141 m long, in 0.05 x 0.1 m
    assert 0.005 < band < 0.05, band
    print(f"self-test: fixed width {df[0]:.3f} -> {df[1]:.3f}; one cell wide {dm[0]:.3f} -> {dm[1]:.3f}; "
          f"A50 uniform {a50(uniform):.3f}, thin band {band:.3f}: ok")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("runs", nargs="*", help="run directories, coarse to fine")
    ap.add_argument("--at-strain", type=float, default=0.105, help="log axial strain (default 0.105)")
    ap.add_argument("--maps", metavar="FIG", help="draw the runs' strain maps (RUN[:LABEL]) to FIG")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    if np is None:
        print("biaxial_field_convergence: needs numpy (Debian: python3-numpy)", file=sys.stderr)
        return 77 if args.self_test else 1
    if args.self_test:
        self_test()
        return 0
    if args.maps:
        specs = [p.split(":", 1) if ":" in p else (p, None) for p in args.runs]
        draw_maps([read_run(p, args.at_strain, label) for p, label in specs], args.maps)
        return 0
    if len(args.runs) < 2:
        ap.error("give at least two runs, coarse to fine")
    runs = [read_run(p, args.at_strain) for p in args.runs]
    rows, fields = compare(runs)
    print("| run | axial strain | eps_dev bin max / mean | A50 (share carrying half the strain) |")
    print("|---|---|---|---|")
    for r, f in zip(runs, fields):
        print(f"| {r['label']} | {r['eps']:.4f} | {np.nanmax(f):.3f} / {np.nanmean(f):.3f} | "
              f"{a50(r):.3f} |")
    print()
    print("| coarser | finer | relative RMS difference of the binned fields |")
    print("|---|---|---|")
    for a, b, d in rows:
        print(f"| {a} | {b} | {d:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
