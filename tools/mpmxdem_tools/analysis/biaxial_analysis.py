#!/usr/bin/python3
"""Figures of the plane-strain biaxial test (docs/validation/biaxial.md): global stress ratio against the
pure DEM, shear band angle and thickness from the points' accumulated deviatoric strain, and the
Roscoe / Coulomb angles from phi and psi of our own pure DEM tests.

  tools/mpmxdem-tools biaxial_analysis RUN [RUN ...] [--dem CSV[:LABEL] ...]
      [--triaxial docs/data/triaxial_dem_30k/dem_series.csv] [--figures DIR] [--prefix biaxial_]

RUN: an `mpmxdem run` output directory of a jobs/biaxial_plane_strain_*.toml job (results.h5 and
job.toml); RUN:LABEL names it in the legends. --dem: `mpmxdem dem` series (dem_series.csv) of a
plane-strain (dem.loading.type = "biaxial") test; the first one gives phi and psi. Conventions:
compression positive for stresses and strains here; axial strain logarithmic; the stress ratio is
sigma_a / sigma_r (MPM: the platens' reaction over the platen area, over the side pressure).
"""

import argparse
import math
import os
import sys

import numpy as np

from . import band_fit  # noqa: E402 (the fit beside this tool)
from .. import readers

P_CONF_DEFAULT = 1e5


def dem_series(path):
    import pandas as pd

    d = pd.read_csv(path)
    out = {"eps": d["eps_a"].to_numpy(), "ratio": (d["sig_a"] / d["sig_r"]).to_numpy(),
           "eps_v": d["eps_v"].to_numpy(), "sig_a": d["sig_a"].to_numpy(),
           "sig_r": d["sig_r"].to_numpy()}
    return out


def friction_dilatancy(s, window=0.005):
    """phi at the peak of sigma_a / sigma_r and psi from the slope d eps_v / d eps_a fitted over
    +/- window around the peak: sin psi = -d eps_v / (2 d eps_a - d eps_v) (Vermeer & de Borst
    1984; exact in plane strain, the usual convention in triaxial compression); eps_v
    compression positive, so a dilating sample gives psi > 0."""
    i = int(np.argmax(s["ratio"]))
    r = s["ratio"][i]
    phi = math.degrees(math.asin((r - 1.0) / (r + 1.0)))
    e0 = s["eps"][i]
    m = (s["eps"] > e0 - window) & (s["eps"] < e0 + window)
    slope = np.polyfit(s["eps"][m], s["eps_v"][m], 1)[0]
    psi = math.degrees(math.asin(-slope / (2.0 - slope)))
    return {"eps_peak": e0, "ratio_peak": r, "phi": phi, "psi": psi, "slope": slope}


def hencky_dev(F):
    """Equivalent deviatoric Hencky strain sqrt(2/3 e':e') of each row of F (n x 9)."""
    F = F.reshape(-1, 3, 3)
    C = np.einsum("nki,nkj->nij", F, F)
    w, v = np.linalg.eigh(C)
    E = np.einsum("nij,nj,nkj->nik", v, 0.5 * np.log(w), v)
    tr = np.trace(E, axis1=1, axis2=2)
    dev = E - tr[:, None, None] / 3.0 * np.eye(3)
    return np.sqrt(2.0 / 3.0 * np.einsum("nij,nij->n", dev, dev))


class Run:
    def __init__(self, path, label=None):
        self.path = path
        self.label = label or os.path.basename(os.path.normpath(path))
        job = readers.job(path, resolved=False)
        body = job["mpm"]["body"][0]
        self.h = job["mpm"]["grid"]["spacing"][0]
        self.W = body["max"][0] - body["min"][0]
        self.T = body["max"][1] - body["min"][1]
        self.H = body["max"][2] - body["min"][2]
        self.lo = (body["min"][0], body["min"][2])  # the specimen's corner in (x, z) [m]
        self.cells = (round(self.W / self.h), round(self.H / job["mpm"]["grid"]["spacing"][2]))
        f = readers.results(path)
        self.f = f
        self.names = readers.constraint_names(f)
        self.platens = [k for k, n in enumerate(self.names) if n.startswith("platen")]
        self.base = self.names.index("base")
        R = f["constraints/reaction"][:]
        D = f["constraints/displacement"][:]
        self.time = f["time"][:]
        self.eps = -np.log(1.0 + D[:, self.platens[0], 2] / self.H)
        A = self.W * self.T
        self.sig_a = -R[:, self.platens, 2].sum(axis=1) / A
        self.sig_base = R[:, self.base, 2] / A
        st = f["points/stress"][:]
        vol = f["points/volume"][:]
        # The global axial stress: int sigma_zz dV / (H_current A), which equals the platen's
        # reaction over A in equilibrium (only the top platen contributes to int z t_z dA) and
        # is free of the step-to-step oscillation a mass-scaled reaction carries.
        h_cur = self.H + D[:, self.platens[0], 2]
        self.sig_int = -np.einsum("tn,tn->t", vol, st.reshape(len(self.time), -1, 9)[:, :, 8]) / \
            (h_cur * A)
        self.ratio = self.sig_int / P_CONF_DEFAULT
        self.ratio_platen = self.sig_a / P_CONF_DEFAULT
        # Volume average of the points' stress (compression positive), for the equilibrium check.
        self.sig_mean = -np.einsum("tn,tnij->tij", vol, st.reshape(len(self.time), -1, 3, 3)) / \
            vol.sum(axis=1)[:, None, None]
        self.x = f["points/x"][:]
        self.F = f["points/F"][:]

    def row_at(self, eps):
        """The first output row at or past log axial strain eps (the last row if never)."""
        if eps is None:
            return len(self.time) - 1
        k = np.nonzero(self.eps >= eps)[0]
        return int(k[0]) if k.size else len(self.time) - 1

    def eps_dev(self, row=-1):
        return hencky_dev(self.F[row])


def first_peak(r):
    """The output row of run r's first peak of sigma_a / sigma_r: its running maximum before the
    ratio first falls 5 % below it (post-peak the ratio oscillates and may come back above it)."""
    runmax = np.maximum.accumulate(r.ratio)
    drop = np.nonzero(r.ratio < 0.95 * runmax)[0]
    return int(np.argmax(r.ratio[: drop[0]])) if drop.size else int(np.argmax(r.ratio))


def band_at(r, row):
    """The shear band of run r at output row `row`, fitted to the points' accumulated deviatoric
    strain (band_fit) away from the platens: the points of the first and last cell rows (the rough
    platens' dead zones and corners) are left out. Returns theta (deg from +x), d0 and width [m]
    of the single band, its angle from the horizontal (`incl`), the conjugate X's angle, its other
    band's width and balance, the strain field and the mask of the points fitted."""
    x, z = r.x[row][:, 0], r.x[row][:, 2]
    e = r.eps_dev(row)
    top = r.H * math.exp(-r.eps[row])
    inner = (z > r.h) & (z < top - r.h)
    th, d0, _ = band_fit.single(x[inner], z[inner], e[inner], r.h)
    width = band_fit.thickness(x[inner], z[inner], e[inner], r.h, th, d0)
    # The conjugate pair (an X of two mirror bands, as rough platens make).
    c = band_fit.conjugate(x[inner], z[inner], e[inner], r.h)
    th2 = c["angle"] if th >= 90 else 180.0 - c["angle"]  # the other sense than `th`
    d2 = c["d_rising"] if th >= 90 else c["d_falling"]
    width2 = band_fit.thickness(x[inner], z[inner], e[inner], r.h, th2, d2)
    return {"theta": th, "d0": d0, "width": width, "incl": min(th, 180.0 - th),
            "conjugate": c["angle"], "conjugate_width": width2, "balance": c["balance"],
            "eps_dev": e, "inner": inner}


# Axial-strain windows over which the stress ratio is averaged (it swings by +-2-5 % from row to row
# on a localising specimen): docs/design/mpm.md, "Mass scaling" and "Regularisation".
WINDOWS = [(0.01, 0.02), (0.04, 0.06), (0.09, 0.105)]


def window_means(r):
    """sigma_a/sigma_r (the global ratio) of run r averaged over each of WINDOWS (nan where the run
    has no row)."""
    out = []
    for lo, hi in WINDOWS:
        sel = (r.eps >= lo - 1e-9) & (r.eps <= hi + 1e-9)
        out.append(float(r.ratio[sel].mean()) if sel.any() else float("nan"))
    return out


def print_windows(paths):
    print("| run | " + " | ".join("mean over %g-%g %%" % (100 * lo, 100 * hi) for lo, hi in WINDOWS) + " |")
    print("|---|" + "---|" * len(WINDOWS))
    for path in paths:
        spec, _, label = path.partition(":")
        print(f"| {label or os.path.basename(os.path.normpath(spec))} | "
              + " | ".join("%.2f" % m for m in window_means(Run(spec))) + " |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--dem", action="append", default=[])
    ap.add_argument("--triaxial", default=None)
    ap.add_argument("--figures", default=None)
    ap.add_argument("--prefix", default="biaxial_")
    ap.add_argument("--pre-peak-from", type=float, default=0.002)
    ap.add_argument("--at-strain", type=float, default=None,
                    help="band and maps at the first row past this axial strain (default: the last row)")
    ap.add_argument("--windows", action="store_true",
                    help="print only each run's sigma_a/sigma_r averaged over the axial-strain windows "
                         + ", ".join("%g-%g %%%%" % (100 * lo, 100 * hi) for lo, hi in WINDOWS))
    a = ap.parse_args()
    if a.windows:
        print_windows(a.runs)
        return

    dems = []
    for spec in a.dem:
        path, _, label = spec.partition(":")
        dems.append((label or path, dem_series(path)))
    if not dems:
        sys.exit("biaxial_analysis: give at least one --dem plane-strain series")
    ref_label, ref = dems[0]
    fd = friction_dilatancy(ref)
    print(f"pure DEM plane strain ({ref_label}): peak sigma_a/sigma_r {fd['ratio_peak']:.3f} at "
          f"eps_a {100 * fd['eps_peak']:.2f} %: phi {fd['phi']:.1f} deg; d eps_v / d eps_a at "
          f"the peak {fd['slope']:.3f}: psi {fd['psi']:.1f} deg")
    for label, s in dems[1:]:
        o = friction_dilatancy(s)
        print(f"pure DEM plane strain ({label}): peak ratio {o['ratio_peak']:.3f} at "
              f"{100 * o['eps_peak']:.2f} %: phi {o['phi']:.1f} deg, psi {o['psi']:.1f} deg")
    if a.triaxial:
        t = dem_series(a.triaxial)
        o = friction_dilatancy(t)
        print(f"pure DEM triaxial ({a.triaxial}): peak ratio {o['ratio_peak']:.3f} at "
              f"{100 * o['eps_peak']:.2f} %: phi {o['phi']:.1f} deg, psi {o['psi']:.1f} deg")
    roscoe = 45.0 + fd["psi"] / 2.0
    coulomb = 45.0 + fd["phi"] / 2.0
    print(f"band angles from the horizontal (sigma_3 direction): Roscoe 45 + psi/2 = {roscoe:.1f}, "
          f"Coulomb 45 + phi/2 = {coulomb:.1f}, Arthur (mean) {(roscoe + coulomb) / 2:.1f} deg")

    runs = []
    for spec in a.runs:
        path, _, label = spec.partition(":")
        runs.append(Run(path, label or None))
    print()
    print("| run | cells | RVEs | first peak ratio (eps_a) | ratio at 10 % | pre-peak error vs DEM, max (RMS) "
          "| platen reaction vs int sigma_zz dV (RMS) | band angle | band thickness | thickness / h "
          "| conjugate X: angle, other band's thickness, balance | band measured at eps_a |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in runs:
        i = first_peak(r)
        # Before the peak: from pre_peak_from to the first of the two peaks (the DEM's, the run's).
        m = (r.eps >= a.pre_peak_from) & (r.eps <= min(fd["eps_peak"], r.eps[i]))
        rel = r.ratio[m] / np.interp(r.eps[m], ref["eps"], ref["ratio"]) - 1.0
        err = (f"{100 * np.max(np.abs(rel)):.1f} % ({100 * np.sqrt(np.mean(rel ** 2)):.1f} %)"
               if rel.size else "-")
        r10 = np.interp(0.10, r.eps, r.ratio) if r.eps[-1] >= 0.10 else float("nan")
        post = r.eps > 0.0025
        bal = np.sqrt(np.mean(((r.sig_a[post] - r.sig_int[post]) / r.sig_int[post]) ** 2))
        r.row = r.row_at(a.at_strain)
        x, z = r.x[r.row][:, 0], r.x[r.row][:, 2]
        b = band_at(r, r.row)
        th, d0, width, e, inner = b["theta"], b["d0"], b["width"], b["eps_dev"], b["inner"]
        r.band = (th, d0, width, e)
        r.conj = (b["conjugate"], b["conjugate_width"], b["balance"])
        t = math.radians(th)
        dist = np.abs(-x * math.sin(t) + z * math.cos(t) - d0)
        r.in_band = inner & (dist <= max(width, r.h) / 2.0)
        r.out_band = inner & (dist > max(width, r.h))
        incl = min(th, 180.0 - th)
        r.reading = (f"{r.label}: first peak sigma_a/sigma_r {r.ratio[i]:.2f} at eps_a "
                     f"{100 * r.eps[i]:.1f} % (pure DEM {fd['ratio_peak']:.2f} at "
                     f"{100 * fd['eps_peak']:.1f} %); at eps_a {100 * r.eps[r.row]:.1f} % a shear band at "
                     f"{incl:.1f} deg from the horizontal (Roscoe {roscoe:.1f}, Coulomb {coulomb:.1f}), "
                     f"{1e3 * width:.1f} mm thick = {width / r.h:.1f} cells")
        print(f"| {r.label} | {r.cells[0]} x {r.cells[1]} | {len(x)} | {r.ratio[i]:.2f} "
              f"({100 * r.eps[i]:.2f} %) | {r10:.2f} | {err} | {100 * bal:.1f} % | {incl:.1f} deg | "
              f"{1e3 * width:.1f} mm | {width / r.h:.2f} | {r.conj[0]:.1f} deg, {1e3 * r.conj[1]:.1f} mm, {r.conj[2]:.2f} | {100 * r.eps[r.row]:.2f} % |")
    print()
    for r in runs:
        print(r.reading)
    print()
    print("| run | RVEs with p < 1 kPa at the end | e in / out of the band | Z in / out | "
          "MPM steps, wall (log.txt) |")
    print("|---|---|---|---|---|")
    for r in runs:
        f = r.f
        p_end = f["points/p"][r.row]
        ev = f["points/void_ratio"][r.row]
        zz = f["points/z"][r.row]
        wall = "-"
        log = os.path.join(r.path, "log.txt")
        if os.path.exists(log):
            for line in open(log):
                if "info: done:" in line and "wall" in line:
                    wall = line.split("done:")[1].split(";")[0].strip()
        if not r.in_band.any() or not r.out_band.any():
            print(f"| {r.label} | {int((p_end < 1e3).sum())} of {len(p_end)} | no band | | {wall} |")
            continue
        print(f"| {r.label} | {int((p_end < 1e3).sum())} of {len(p_end)} | "
              f"{np.nanmean(ev[r.in_band]):.3f} / {np.nanmean(ev[r.out_band]):.3f} | "
              f"{np.nanmean(zz[r.in_band]):.2f} / {np.nanmean(zz[r.out_band]):.2f} | "
              f"{wall} |")
    print()
    for r in runs:
        sm = r.sig_mean[r.row]
        print(f"{r.label}: at eps_a {100 * r.eps[r.row]:.2f} % (last row {100 * r.eps[-1]:.2f} %); "
              f"volume-mean sigma_xx "
              f"{sm[0, 0] / 1e3:.1f} kPa, sigma_zz {sm[2, 2] / 1e3:.1f} kPa against platen "
              f"{r.sig_a[r.row] / 1e3:.1f} kPa; eps_dev max {r.band[3].max():.3f}, median "
              f"{np.median(r.band[3]):.3f}")

    if not a.figures:
        return
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    os.makedirs(a.figures, exist_ok=True)
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for label, s in dems:
        ax[0].plot(100 * s["eps"], s["ratio"], "k-" if label == ref_label else "k--", lw=1.2,
                   label=f"pure DEM, {label}")
        ax[1].plot(100 * s["eps"], 100 * s["eps_v"], "k-" if label == ref_label else "k--",
                   lw=1.2, label=f"pure DEM, {label}")
    for r in runs:
        ax[0].plot(100 * r.eps, r.ratio, "-", lw=1.2, label=f"MPM x DEM, {r.label}")
        vol = r.f["points/volume"][:].sum(axis=1)
        ax[1].plot(100 * r.eps, -100 * np.log(vol / vol[0]), "-", lw=1.2,
                   label=f"MPM x DEM, {r.label}")
    ax[0].set_xlabel("axial strain [%]")
    ax[0].set_ylabel("sigma_a / sigma_r [-]")
    ax[1].set_xlabel("axial strain [%]")
    ax[1].set_ylabel("volumetric strain [%] (compression +)")
    ax[0].legend(fontsize=7)
    ax[0].grid(alpha=0.3)
    ax[1].grid(alpha=0.3)
    fig.tight_layout()
    p = os.path.join(a.figures, a.prefix + "stress_strain.png")
    fig.savefig(p, dpi=130)
    print("wrote", p)

    fig, ax = plt.subplots(1, len(runs), figsize=(3.6 * len(runs), 6.0), squeeze=False)
    vmax = max(np.percentile(r.band[3], 99) for r in runs)
    for k, r in enumerate(runs):
        x, z = r.x[r.row][:, 0], r.x[r.row][:, 2]
        th, d0, width, e = r.band
        sc = ax[0, k].scatter(1e3 * x, 1e3 * z, c=e, s=max(2.0, 900.0 / len(x) ** 0.5 * 1.5),
                              marker="s", cmap="viridis", vmin=0, vmax=vmax)
        t = math.radians(th)
        # The band's line and, through its centre, the Roscoe and Coulomb lines of the same sense.
        xc = np.clip(np.mean(x), x.min(), x.max())
        zc = (d0 + xc * math.sin(t)) / math.cos(t) if abs(math.cos(t)) > 1e-9 else np.mean(z)
        sgn = 1.0 if th < 90 else -1.0
        for ang, style, lab in ((th if th < 90 else 180 - th, "r-", f"fit {min(th, 180 - th):.0f}"),
                                (roscoe, "w--", f"Roscoe {roscoe:.0f}"),
                                (coulomb, "m:", f"Coulomb {coulomb:.0f}")):
            tt = math.radians(ang)
            s = np.linspace(-0.6, 0.6, 2) * r.H
            ax[0, k].plot(1e3 * (xc + s * math.cos(tt) * sgn), 1e3 * (zc + s * math.sin(tt)), style,
                          lw=1.3, label=lab)
        ax[0, k].set_xlim(1e3 * (x.min() - r.h), 1e3 * (x.max() + r.h))
        ax[0, k].set_ylim(-1e3 * r.h / 2, 1e3 * (r.H + r.h / 2))
        ax[0, k].set_aspect("equal")
        ax[0, k].set_title(f"{r.label}: {r.cells[0]} x {r.cells[1]} cells\n"
                           f"eps_a = {100 * r.eps[r.row]:.1f} %", fontsize=9)
        ax[0, k].set_xlabel("x [mm]")
        ax[0, k].legend(fontsize=7, loc="lower right")
    ax[0, 0].set_ylabel("z [mm]")
    fig.colorbar(sc, ax=ax[0, :].tolist(), shrink=0.8, label="accumulated deviatoric strain [-]")
    p = os.path.join(a.figures, a.prefix + "strain_maps.png")
    fig.savefig(p, dpi=130)
    print("wrote", p)


if __name__ == "__main__":
    main()
