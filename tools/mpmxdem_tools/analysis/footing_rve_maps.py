#!/usr/bin/python3
"""What the RVEs look like under a strip footing (docs/validation/footing.md): maps over the points'
current positions, at the output row nearest a settlement s/B, of (1) the shear strain
eps_1 - eps_3 of the point's deformation gradient (logarithmic principal strains in the xz plane),
(2) the RVE's void ratio, (3) its coordination number and (4) its fabric anisotropy in the xz plane,
(f_1 - f_3) / (f_1 + f_3) of the contact-normal fabric tensor; and, printed, the means of these in
the sheared zone (shear strain above a threshold) and outside it. Reads results.h5 (h5py) and the
footing's half-width from the run's resolved job (tools/mpmxdem_tools/analysis/footing_curves.py).

    tools/mpmxdem-tools footing_rve_maps RUN [--at 0.4] [--zoom 4] [--shear 0.1] [--out maps.png]

--zoom: the maps show x up to ZOOM x B and the top ZOOM/2 x B of the layer.
"""
import argparse
import os

import numpy as np

from . import footing_curves
from .. import readers


def principal_xz(t):
    """Principal values (major, minor) of the xz parts of row-major 3 x 3 tensors t[..., 9]."""
    a, b, c = t[..., 0], t[..., 2], t[..., 8]  # xx, xz, zz
    m, r = 0.5 * (a + c), np.sqrt((0.5 * (a - c)) ** 2 + b ** 2)
    return m + r, m - r


def shear_strain(F):
    """eps_1 - eps_3 in the xz plane from deformation gradients F[..., 9] (row-major)."""
    Fm = F.reshape(F.shape[:-1] + (3, 3))
    C = np.einsum("...ki,...kj->...ij", Fm, Fm).reshape(F.shape)
    l1, l3 = principal_xz(C)
    return 0.5 * (np.log(l1) - np.log(np.maximum(l3, 1e-300)))


def surface(run):
    """The layer's initial surface z [m]: the top of its body."""
    return readers.job(run)["mpm"]["body"][0]["max"][2]


def fields(run, at):
    half, _ = footing_curves.footing_geometry(run)
    sb, _ = footing_curves.curve(run)
    with readers.results(run) as f:
        t_rows = f["time"][:]
        # results.h5's rows and reactions.csv's rows are the same output steps
        k = int((sb - at).abs().idxmin())
        k = min(k, len(t_rows) - 1)
        x = f["points/x"][k]
        fab1, fab3 = principal_xz(f["rve/fabric"][k])
        out = {"x": x[:, 0], "z": x[:, 2], "shear strain": shear_strain(f["points/F"][k]),
               "void ratio": f["rve/void_ratio"][k], "coordination": f["rve/z"][k],
               "fabric anisotropy": (fab1 - fab3) / np.maximum(fab1 + fab3, 1e-300)}
    return out, float(sb[k]), 2 * half


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run")
    ap.add_argument("--at", type=float, default=0.4, help="settlement s/B of the row shown")
    ap.add_argument("--zoom", type=float, default=4.0)
    ap.add_argument("--shear", type=float, default=0.1, help="shear strain that marks the sheared zone")
    ap.add_argument("--out")
    a = ap.parse_args()
    d, sb, B = fields(a.run, a.at)
    sheared = d["shear strain"] > a.shear
    print("row at s/B = %.3f: %d of %d points sheared beyond %g" % (sb, sheared.sum(), sheared.size, a.shear))
    for name in ("void ratio", "coordination", "fabric anisotropy"):
        v = d[name]
        print("  %-18s sheared %.3f (sd %.3f)   elsewhere %.3f (sd %.3f)" % (
            name, v[sheared].mean() if sheared.any() else float("nan"),
            v[sheared].std() if sheared.any() else float("nan"), v[~sheared].mean(), v[~sheared].std()))
    if not a.out:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    top = surface(a.run)
    names = ("shear strain", "void ratio", "coordination", "fabric anisotropy")
    fig, axes = plt.subplots(2, 2, figsize=(10, 5.6))
    for ax, name in zip(axes.flat, names):
        v = d[name]
        lo, hi = np.percentile(v, [2, 98])
        sc = ax.scatter(d["x"] / B, (d["z"] - top) / B, c=v, s=6, marker="s", cmap="viridis", vmin=lo, vmax=hi)
        ax.set_xlim(0, a.zoom)
        ax.set_ylim(-a.zoom / 2, 0.3)
        ax.set_aspect("equal")
        ax.set_title(name, fontsize=9)
        ax.set_xlabel("x / B")
        ax.set_ylabel("(z - surface) / B")
        ax.plot([0, 0.5], [-sb, -sb], color="r", lw=3)  # the footing's base
        fig.colorbar(sc, ax=ax, shrink=0.8)
    fig.suptitle("%s at s/B = %.2f" % (os.path.basename(a.run.rstrip("/")), sb), fontsize=10)
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)
    print("wrote", a.out)


if __name__ == "__main__":
    main()
