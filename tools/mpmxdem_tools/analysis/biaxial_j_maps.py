#!/usr/bin/python3
"""Maps of the points' volume ratio J = det F of plane-strain biaxial runs (docs/validation/biaxial.md): one
panel per run at the output row nearest a given axial strain, points coloured by J (crushed rows
blue, torn rows red), with the counts of crushed (J < 0.9) and torn (J > 1.3) points and of RVEs
without contacts in the title. For the inter-cell mode of linear shape functions at low mass
scaling, and its absence with uGIMP.

  tools/mpmxdem-tools biaxial_j_maps RUN:LABEL:STRAIN [RUN:LABEL:STRAIN ...] --out FIG.png
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from .. import readers


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("panels", nargs="+", help="RUN:LABEL:STRAIN (STRAIN: log axial strain, e.g. 0.04)")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    fig, axs = plt.subplots(1, len(a.panels), figsize=(3.8 * len(a.panels), 5.4), squeeze=False,
                            layout="constrained")
    for ax, spec in zip(axs[0], a.panels):
        run, label, strain = spec.rsplit(":", 2)
        with readers.results(run) as f:
            eps = f["means/eps_ax"][:]
            i = int(np.argmin(abs(eps - float(strain))))
            x = f["points/x"][i]
            J = np.linalg.det(f["points/F"][i].reshape(-1, 3, 3))
            z = f["rve/z"][i]
        sc = ax.scatter(1e3 * x[:, 0], 1e3 * x[:, 2], c=J, cmap="coolwarm", vmin=0.7, vmax=1.3, s=14)
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm]")
        ax.set_title(f"{label}, eps_a {100 * eps[i]:.1f} %\nJ {J.min():.2f}-{J.max():.2f}; "
                     f"J<0.9: {np.sum(J < 0.9)}, J>1.3: {np.sum(J > 1.3)}, Z=0: {np.sum(z == 0)}",
                     fontsize=8)
    axs[0][0].set_ylabel("z [mm]")
    fig.colorbar(sc, ax=axs[0].tolist(), label="J = det F", shrink=0.8)
    fig.savefig(a.out, dpi=110)
    print("wrote", a.out)


if __name__ == "__main__":
    main()
