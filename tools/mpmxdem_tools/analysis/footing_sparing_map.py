#!/usr/bin/python3
"""Where sparing spares, on a strip footing (docs/validation/speed.md, "Sparing on a strip footing"):
maps over the points' initial positions of (left) the DEM steps per MPM step of each RVE in the
run without sparing and (right) the share of its MPM steps that the spared run spared, from the
rows of results.h5 (every output.every-th step).

    tools/mpmxdem-tools footing_sparing_map REF_RUN SPARED_RUN --out map.png
"""
import argparse
import os

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from .. import readers


def per_point(run):
    """(initial x, initial z, mean DEM steps per row, share of rows spared) by point slot."""
    with readers.results(run) as f:
        x0 = f["points/x"][0]
        pid = f["points/id"][:]
        rid = f["rve/id"][:]
        slot_of = {int(i): k for k, i in enumerate(rid)}
        order = np.array([slot_of[int(i)] for i in pid])  # the RVE of each point
        steps = f["rve/dem_steps"][1:][:, order].mean(axis=0)
        spared = ((f["rve/guards"][1:][:, order] >> 16) & 1).mean(axis=0)
    return x0[:, 0], x0[:, 2], steps, spared


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("ref")
    ap.add_argument("spared")
    ap.add_argument("--out", required=True)
    ap.add_argument("--title", default="")
    a = ap.parse_args()
    x, z, steps, _ = per_point(a.ref)
    xs, zs, _, spared = per_point(a.spared)
    assert np.array_equal(x, xs) and np.array_equal(z, zs)
    w = x.max() - x.min()
    h = z.max() - z.min()
    fig, axes = plt.subplots(1, 2, figsize=(11, 11 * h / (2 * w) + 1.2))
    im = axes[0].scatter(x, z, c=steps, s=12, marker="s", cmap="viridis",
                         norm=matplotlib.colors.LogNorm(vmin=1, vmax=max(steps.max(), 2)))
    fig.colorbar(im, ax=axes[0], shrink=0.8, label="DEM steps per MPM step (no sparing)")
    im = axes[1].scatter(x, z, c=100 * spared, s=12, marker="s", cmap="magma", vmin=0, vmax=100)
    fig.colorbar(im, ax=axes[1], shrink=0.8, label="MPM steps spared [%]")
    for ax in axes:
        ax.set_aspect("equal")
        ax.set_xlabel("x [m] (footing at x < 0.025 on top)")
        ax.set_ylabel("z [m]")
    fig.suptitle(a.title or "%s / %s" % (os.path.basename(a.ref), os.path.basename(a.spared)), fontsize=9)
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    total = steps.sum()
    floor = steps <= 1.05
    print("%d RVEs; %d (%.0f %%) take <= 1.05 DEM steps per MPM step without sparing: %.0f %% of the "
          "DEM steps; spared share: median %.0f %%" % (len(steps), floor.sum(), 100 * floor.mean(),
                                                       100 * steps[floor].sum() / total, 100 * np.median(spared)))


if __name__ == "__main__":
    main()
