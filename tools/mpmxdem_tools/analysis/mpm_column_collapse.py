#!/usr/bin/python3
"""MPM x DEM column collapses (jobs/column_collapse_a*.toml): front, height, deposit, inertial number.

Reads the results.h5 of one or more runs (h5py), writes per run `<tag>_timeseries.csv`,
`<tag>_profiles.csv`, `<tag>_summary.csv` (and `summary.csv`) under --data, and the figures
column_mpm_front.png, column_mpm_profiles.png, column_mpm_inertial.png under --fig, overlaid on the
YADE reference series of docs/data/column_collapse_yade (the longest-running one per a).

Usage: tools/mpmxdem-tools mpm_column_collapse RUN_DIR [RUN_DIR ...] [--data D] [--fig F]

Definitions (docs/validation/column_collapse.md): t* = sqrt(H0 / g); the figures count time from the
release (the `until` of the velocity condition named "gate" in RUN_DIR/job.toml; YADE's columns
release at t = 0), the CSVs from the start of the run; every point carries the volume of its
initial cell share, so the front is the farthest point plus its initial half-width, shifted so
that L(0) = L0 (as YADE's front is corrected by its t = 0 offset); H is the highest point top in
the first cell column at the back wall, shifted so that H(0) = H0. The connected front (dotted)
ends the deposit at the first gap wider than 1.5 cells between the points sorted by x: points
detached ahead of it (RVEs that lost all contacts and flew) are left out. The deposit profile h_vol(x) is
the initial bulk volume of the points in bins of one cell, over the bin's area (the height the
material would have at its initial density, as YADE's h_vol). Macro inertial number per point:
I = gamma_dot d50 / sqrt(p / rho_s), gamma_dot = sqrt(2 D':D') from the finite difference of F
between two output rows (D = sym(dF F^-1) / dt), p the point's pressure (floored at 1 Pa), d50 =
200 um, rho_s = 2650 kg/m^3 (the grains' density). Free flight: an RVE with no contact (rve/z == 0);
near-zero pressure: rve/p below 100 Pa. Kinetic energy: kinetic_over_MgH0 from the points'
velocities (FLIP: a point held by the rough base keeps a velocity it does not move with);
kinetic_motion_over_MgH0 from the points' motion between two output rows (what "at rest" means).
"""
import argparse
import glob
import os
import sys

import matplotlib

from .column_grain_scale import gate_release

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from .. import readers

G = 9.81
D50 = 200e-6
RHO_S = 2650.0
P_LOW = 100.0  # [Pa] "near-zero pressure"


def run_dem_steps(run):
    """The run's DEM steps, all of them (run_summary.json); "" for a run that wrote none or
    stopped on an error (its summary then has no counts: the rows it wrote are still analysed).
    (The sum of results.h5's rve/dem_steps counts only the written rows, every output.every-th
    MPM step: a small fraction of the work.)"""
    s = readers.summary(run, required=False)
    return s.get("dem_steps", "") if s else ""


def analyse(run):
    f = readers.results(run)
    t = f["time"][:]
    x = f["points/x"][:]
    vol0 = f["points/volume"][0]
    vel = f["points/velocity"][:]
    F = f["points/F"][:].reshape(len(t), -1, 3, 3)
    p_pt = f["points/p"][:]
    rz = f["rve/z"][:]
    rp = f["rve/p"][:]
    steps = f["step"][:]
    x0 = x[0]
    # The initial column: the points' box, each point's initial cell share (plane strain in y).
    xs, zs = np.unique(np.round(x0[:, 0], 9)), np.unique(np.round(x0[:, 2], 9))
    dx = xs[1] - xs[0] if len(xs) > 1 else 2 * xs[0]
    dz = zs[1] - zs[0] if len(zs) > 1 else 2 * zs[0]
    L0 = x0[:, 0].max() + dx / 2
    H0 = x0[:, 2].max() + dz / 2
    thick = vol0[0] / (dx * dz)
    a = H0 / L0
    tstar = np.sqrt(H0 / G)
    front = x[:, :, 0].max(axis=1) - x0[:, 0].max() + L0

    def connected_front(xk):
        """The end of the continuous deposit: points sorted by x from the back wall, the deposit
        ends at the first gap wider than 1.5 cells (points detached ahead of it, e.g. RVEs that
        lost their contacts and flew, do not count); shifted like `front`."""
        xs_k = np.sort(xk)
        gaps = np.nonzero(np.diff(xs_k) > 1.5 * dx)[0]
        last = xs_k[gaps[0]] if gaps.size else xs_k[-1]
        return last - x0[:, 0].max() + L0

    front_c = np.array([connected_front(x[k, :, 0]) for k in range(len(t))])
    back = x0[:, 0] < dx  # the first column of points
    hback = x[:, back, 2].max(axis=1) - x0[back, 2].max() + H0
    ek = 0.5 * (vol0[None, :] * (vel ** 2).sum(axis=2)).sum(axis=1)  # per unit bulk density
    ek_norm = ek / (vol0.sum() * G * H0)  # E_k / (M g H0): the density cancels
    # The same from the points' motion between output rows: with mpm.position_update = "grid" a
    # point held by the rough base keeps a FLIP velocity it does not move with, so E_k of the
    # point velocities stays finite in a deposit at rest; this one measures the motion.
    ek_motion = np.zeros(len(t))
    for k in range(1, len(t)):
        vm = (x[k] - x[k - 1]) / (t[k] - t[k - 1])
        ek_motion[k] = 0.5 * (vol0 * (vm ** 2).sum(axis=1)).sum() / (vol0.sum() * G * H0)
    # Inertial number from F between output rows.
    n = len(t)
    inert = np.full((n, x.shape[1]), np.nan)
    for k in range(1, n):
        dtk = t[k] - t[k - 1]
        Fm = 0.5 * (F[k] + F[k - 1])
        ok = np.abs(np.linalg.det(Fm)) > 1e-12  # a stress-free point may be crushed flat
        Fm[~ok] = np.eye(3)
        Lk = (F[k] - F[k - 1]) @ np.linalg.inv(Fm) / dtk
        Lk[~ok] = np.nan
        D = 0.5 * (Lk + np.transpose(Lk, (0, 2, 1)))
        Dd = D - np.trace(D, axis1=1, axis2=2)[:, None, None] * np.eye(3) / 3
        gdot = np.sqrt(2 * (Dd ** 2).sum(axis=(1, 2)))
        inert[k] = gdot * D50 / np.sqrt(np.maximum(p_pt[k], 1.0) / RHO_S)
    flight = (rz <= 0).sum(axis=1)
    lowp = (rp < P_LOW).sum(axis=1)
    # Profiles on bins of one cell.
    nb = int(np.ceil((x[:, :, 0].max() + dx) / dx)) + 1
    edges = np.arange(nb + 1) * dx

    def profile(k):
        hv = np.histogram(x[k, :, 0], bins=edges, weights=vol0)[0] / (dx * thick)
        ht = np.zeros(nb)
        idx = np.clip(np.digitize(x[k, :, 0], edges) - 1, 0, nb - 1)
        np.maximum.at(ht, idx, x[k, :, 2] + dz / 2)
        return 0.5 * (edges[1:] + edges[:-1]), hv, ht

    runout = (front[-1] - L0) / L0
    target = front[0] + 0.99 * (front[-1] - front[0])
    t99 = t[np.argmax(front >= target)] / tstar if front[-1] > front[0] else np.nan
    runout_c = (front_c[-1] - L0) / L0
    target_c = front_c[0] + 0.99 * (front_c[-1] - front_c[0])
    t99_c = t[np.argmax(front_c >= target_c)] / tstar if front_c[-1] > front_c[0] else np.nan
    summ = dict(tag=f"a{a:g}", a=a, rves=x.shape[1], L0_m=L0, H0_m=H0, cell_m=dx, tstar_s=tstar,
                L_f_m=front[-1], H_f_m=hback[-1], runout_over_L0=runout,
                Hf_over_L0=hback[-1] / L0, Hf_over_H0=hback[-1] / H0, t99_over_tstar=t99,
                runout_connected_over_L0=runout_c, t99_connected_over_tstar=t99_c,
                t_end_over_tstar=t[-1] / tstar, Ekpeak_over_MgH0=ek_norm.max(),
                t_Ekpeak_over_tstar=t[np.argmax(ek_norm)] / tstar, Ekend_over_MgH0=ek_norm[-1],
                Ekend_motion_over_MgH0=ek_motion[-1],
                volume_ratio_max=float((f["points/volume"][:] / vol0[None, :]).max()),
                I_max=np.nanmax(inert), I_p95_max=np.nanmax(np.nanpercentile(inert[1:], 95, axis=1)),
                flight_max=int(flight.max()), lowp_max=int(lowp.max()), mpm_steps=int(steps[-1]),
                dem_steps=run_dem_steps(run))
    job = os.path.join(run, "job.toml")
    release = gate_release(job) / tstar if os.path.exists(job) else 0.0
    return dict(t=t, tstar=tstar, release=release, L0=L0, H0=H0, a=a, front=front, front_c=front_c,
                hback=hback, ek=ek_norm,
                ek_motion=ek_motion,
                inert=inert, flight=flight, lowp=lowp, profile=profile, x=x, p=p_pt, summ=summ,
                dx=dx, dz=dz)


def yade_runs():
    """(tag, a, L0, H0, t_end/t*) of every YADE series in --yade: from its summary row, or, for a run
    still going (no summary yet), from runs_meta.csv (written from the runs' logs)."""
    out = {}
    meta = os.path.join(args.yade, "runs_meta.csv")
    if os.path.exists(meta):
        m = np.genfromtxt(meta, delimiter=",", names=True, dtype=None, encoding=None)
        for r in np.atleast_1d(m):
            out[str(r["tag"])] = (float(r["a"]), float(r["L0_m"]), float(r["H0_m"]))
    for s in glob.glob(os.path.join(args.yade, "a*_summary.csv")):
        r = np.genfromtxt(s, delimiter=",", names=True, dtype=None, encoding=None)
        out[str(r["tag"])] = (float(r["a"]), float(r["L0_m"]), float(r["H0_m"]))
    runs = []
    for tag, (a, L0, H0) in out.items():
        ts = os.path.join(args.yade, f"{tag}_timeseries.csv")
        if os.path.exists(ts):
            t_end = np.genfromtxt(ts, delimiter=",", names=True)["t_over_tstar"][-1]
            runs.append((tag, a, L0, H0, t_end))
    return runs


args = None  # set by main()
YADE = []  # filled by main() from --yade


def yade_for(a):
    """The YADE series of the nearest a that ran longest: (path prefix, t_end/t*, L0, H0) or None."""
    best = None
    for tag, ay, L0, H0, t_end in YADE:
        if abs(ay / a - 1) > 0.2:
            continue
        if best is None or t_end > best[1]:
            best = (os.path.join(args.yade, tag), t_end, L0, H0)
    return best


def main():
    global args
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--data", default="docs/data/column_collapse_mpm")
    ap.add_argument("--yade", default="docs/data/column_collapse_yade")
    ap.add_argument("--fig", default="docs/figures")
    args = ap.parse_args()
    os.makedirs(args.data, exist_ok=True)
    os.makedirs(args.fig, exist_ok=True)
    YADE[:] = yade_runs()
    runs = sorted((analyse(r) for r in args.runs), key=lambda r: r["a"])
    keys = list(runs[0]["summ"].keys())
    with open(os.path.join(args.data, "summary.csv"), "w") as out:
        out.write(",".join(keys) + "\n")
        for r in runs:
            s = r["summ"]
            row = ",".join(f"{s[k]:.4g}" if isinstance(s[k], float) else str(s[k]) for k in keys)
            out.write(row + "\n")
            with open(os.path.join(args.data, f"{s['tag']}_summary.csv"), "w") as o:
                o.write(",".join(keys) + "\n" + row + "\n")
            with open(os.path.join(args.data, f"{s['tag']}_timeseries.csv"), "w") as o:
                o.write("t_s,t_over_tstar,L_front_m,L_front_connected_m,H_back_m,kinetic_over_MgH0,"
                        "I_median,I_p95,I_max,rves_no_contact,rves_p_below_100Pa,"
                        "kinetic_motion_over_MgH0\n")
                for k in range(len(r["t"])):
                    i = r["inert"][k]
                    med, p95, mx = ((np.nanmedian(i), np.nanpercentile(i, 95), np.nanmax(i)) if k
                                    else (np.nan,) * 3)
                    o.write(f"{r['t'][k]:.6g},{r['t'][k] / r['tstar']:.4f},{r['front'][k]:.6g},"
                            f"{r['front_c'][k]:.6g},{r['hback'][k]:.6g},{r['ek'][k]:.4g},{med:.4g},{p95:.4g},{mx:.4g},"
                            f"{r['flight'][k]},{r['lowp'][k]},{r['ek_motion'][k]:.4g}\n")
            with open(os.path.join(args.data, f"{s['tag']}_profiles.csv"), "w") as o:
                o.write("t_over_tstar,x_m,h_top_m,h_vol_m\n")
                for k in sorted({0, len(r["t"]) - 1}):
                    xc, hv, ht = r["profile"](k)
                    lab = "final" if k else "0"
                    for j in range(len(xc)):
                        o.write(f"{lab},{xc[j]:.6g},{ht[j]:.6g},{hv[j]:.6g}\n")
    print(open(os.path.join(args.data, "summary.csv")).read())

    # Figures.
    fig, axs = plt.subplots(1, 3, figsize=(14, 4))
    for r in runs:
        tr = r["t"] / r["tstar"] - r["release"]  # from the gate's release, as YADE's
        c = axs[0].plot(tr, (r["front"] - r["L0"]) / r["L0"],
                        label=f"MPM x DEM a = {r['a']:.2g}")[0].get_color()
        axs[0].plot(tr, (r["front_c"] - r["L0"]) / r["L0"], ":", color=c, label="  continuous deposit")
        axs[1].plot(tr, r["hback"] / r["H0"], color=c)
        axs[2].plot(tr, r["ek"], color=c)
        y = yade_for(r["a"])
        if y:
            ts = np.genfromtxt(y[0] + "_timeseries.csv", delimiter=",", names=True)
            L0y = y[2]
            lab = f"YADE {os.path.basename(y[0])}"
            axs[0].plot(ts["t_over_tstar"], (ts["L_front_m"] - ts["L_front_m"][0]) / L0y, "--",
                        color=c, label=lab)
            axs[1].plot(ts["t_over_tstar"], ts["H_back_m"] / ts["H_back_m"][0], "--", color=c)
            axs[2].plot(ts["t_over_tstar"], ts["kinetic_over_MgH0"], "--", color=c)
    axs[0].set_ylabel("(L(t) - L0) / L0")
    axs[1].set_ylabel("H(t) / H0 (back wall)")
    axs[2].set_ylabel("E_k / (M g H0)")
    axs[2].set_yscale("log")
    for ax in axs:
        ax.set_xlabel("t / t* from the release (MPM x DEM: after the gate's `until`)")
        ax.grid(alpha=0.3)
    axs[0].legend(fontsize=7)
    fig.suptitle("Column collapse: MPM x DEM (solid, translational E_k) against YADE (dashed)")
    fig.tight_layout()
    fig.savefig(os.path.join(args.fig, "column_mpm_front.png"), dpi=130)

    fig, axs = plt.subplots(len(runs), 1, figsize=(9, 2.6 * len(runs)), squeeze=False)
    for ax, r in zip(axs[:, 0], runs):
        xc, hv, ht = r["profile"](0)
        ax.step(xc / r["L0"], hv / r["L0"], where="mid", color="0.6", label="MPM x DEM t = 0")
        xc, hv, ht = r["profile"](len(r["t"]) - 1)
        ax.step(xc / r["L0"], hv / r["L0"], where="mid", color="C0",
                label=f"MPM x DEM t = {r['t'][-1] / r['tstar']:.2f} t* (h_vol)")
        ax.plot(r["x"][-1, :, 0] / r["L0"], r["x"][-1, :, 2] / r["L0"], ".", ms=2, color="C0")
        y = yade_for(r["a"])
        if y:
            pr = pd.read_csv(y[0] + "_profiles.csv", dtype={"t_over_tstar": str})
            L0y = y[2]
            fin = pr[pr.t_over_tstar == "final"]
            if len(fin) == 0:  # a run still going: its latest profile
                last = max(float(v) for v in pr.t_over_tstar)
                fin = pr[pr.t_over_tstar.astype(float) == last]
            ax.plot(fin.x_m / L0y, fin.h_vol_m / L0y, color="C3",
                    label=f"YADE {os.path.basename(y[0])}, t = {fin.t_over_tstar.iloc[0]} t* "
                    f"(run to {y[1]:.2f} t*)")
        xmax = r["x"][-1, :, 0].max() / r["L0"] + 0.5
        if y:
            xmax = max(xmax, fin.x_m[fin.h_vol_m > 0].max() / L0y + 0.3)
        ax.set_xlim(0, xmax)
        ax.set_ylabel("h / L0")
        ax.set_title(f"a = {r['a']:.2g}", fontsize=9)
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
    axs[-1, 0].set_xlabel("x / L0")
    fig.tight_layout()
    fig.savefig(os.path.join(args.fig, "column_mpm_profiles.png"), dpi=130)

    fig, axs = plt.subplots(1, 2, figsize=(11, 4))
    for r in runs:
        tr = r["t"] / r["tstar"] - r["release"]
        c = axs[0].plot(tr[1:], np.nanmedian(r["inert"][1:], axis=1), label=f"a = {r['a']:.2g} median")[
            0].get_color()
        axs[0].plot(tr[1:], np.nanpercentile(r["inert"][1:], 95, axis=1), "--", color=c, label="95 %")
        axs[1].plot(tr, r["flight"], color=c, label=f"a = {r['a']:.2g} no contact")
        axs[1].plot(tr, r["lowp"], ":", color=c, label=f"p < {P_LOW:g} Pa")
    axs[0].set_yscale("log")
    axs[0].axhline(1e-3, color="k", lw=0.8)
    axs[0].set_ylabel("macro inertial number I (points)")
    axs[1].set_ylabel("RVEs")
    for ax in axs:
        ax.set_xlabel("t / t* from the release (MPM x DEM: after the gate's `until`)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(args.fig, "column_mpm_inertial.png"), dpi=130)
    sys.exit(0)



if __name__ == "__main__":
    main()
