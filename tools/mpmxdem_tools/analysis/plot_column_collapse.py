#!/usr/bin/python3
"""Figures and table of the YADE granular column collapses (tools/mpmxdem_tools/references/yade_column_collapse.py).

  tools/mpmxdem-tools plot_column_collapse [--data docs/data/column_collapse_yade] [--fig docs/figures]

Reads every <tag>_summary.csv, <tag>_timeseries.csv and <tag>_profiles.csv in --data, writes
  <data>/summary.csv                      all summary rows, one per run
  <fig>/column_profiles.png               deposit h(x)/L0 against x/L0 at t/t* = 0, 1, 2, 3, ... and at the end
  <fig>/column_front.png                  (L(t) - L0)/L0, H(t)/H0 and E_k/(M g H0) against t/t*
  <fig>/column_runout_scaling.png         runout and final height against a, with the laboratory power laws
and prints the fitted exponents (log-log least squares over the runs of the largest N per a).
"""
import argparse
import glob
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
ap.add_argument("--data", default="docs/data/column_collapse_yade")
ap.add_argument("--fig", default="docs/figures")
args = ap.parse_args()
os.makedirs(args.fig, exist_ok=True)

rows = [pd.read_csv(p) for p in sorted(glob.glob(os.path.join(args.data, "*_summary.csv")))]
if not rows:
    raise SystemExit(f"no *_summary.csv in {args.data}")
sm = pd.concat(rows, ignore_index=True).sort_values(["N", "a"])
# the back-wall height estimator (highest grain top in the two bins next to the wall) reads a few percent below
# H0 on the column at rest (wall layering): H_f is also given relative to its own value at t = 0
extra = {"Hback0_over_H0": [], "Hf_over_Hback0": [], "Ekpeak_over_MgH0": [], "t_Ekpeak_over_tstar": [],
         "runout_maxgrain_over_L0": []}
for _, r in sm.iterrows():
    ts = pd.read_csv(os.path.join(args.data, f"{r.tag}_timeseries.csv"))
    extra["Hback0_over_H0"].append(round(ts.H_back_m.iloc[0] / r.H0_m, 4))
    extra["Hf_over_Hback0"].append(round(ts.H_back_m.iloc[-1] / ts.H_back_m.iloc[0], 4))
    k = ts.kinetic_over_MgH0.idxmax()
    extra["Ekpeak_over_MgH0"].append(float(f"{ts.kinetic_over_MgH0[k]:.4g}"))
    extra["t_Ekpeak_over_tstar"].append(round(ts.t_over_tstar[k], 3))
    extra["runout_maxgrain_over_L0"].append(
        round((ts.L_maxgrain_m.iloc[-1] - ts.L_maxgrain_m.iloc[0]) / r.L0_m, 4))
for k, v in extra.items():
    sm[k] = v
sm.to_csv(os.path.join(args.data, "summary.csv"), index=False)
cols = ["tag", "a", "N", "L0_m", "H0_m", "phi0", "runout_over_L0", "runout_maxgrain_over_L0", "Hf_over_L0",
        "Hf_over_H0", "Hf_over_Hback0", "t99_over_tstar", "t_ek1pc_over_tstar", "t_Ekpeak_over_tstar",
        "Ekpeak_over_MgH0", "t_end_over_tstar", "end_reason", "prep_steps", "collapse_steps", "wall_s"]
print("| " + " | ".join(cols) + " |")
print("|" + "---|" * len(cols))
for _, r in sm.iterrows():
    print("| " + " | ".join(str(r[c]) for c in cols) + " |")

colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]

# --- profiles ---------------------------------------------------------------------------------
fig, axes = plt.subplots(len(sm), 1, figsize=(7, 2.3 * len(sm)), squeeze=False)
for ax, (_, r) in zip(axes[:, 0], sm.iterrows()):
    pr = pd.read_csv(os.path.join(args.data, f"{r.tag}_profiles.csv"), dtype={"t_over_tstar": str})
    L0, H0 = r.L0_m, r.H0_m
    ax.plot([0, L0 / L0, L0 / L0], [H0 / L0, H0 / L0, 0], "k:", lw=1, label="initial column")
    labels = [s for s in pr.t_over_tstar.unique() if s != "final"] + ["final"]
    for i, s in enumerate(labels):
        p = pr[pr.t_over_tstar == s]
        if p.empty:
            continue
        lw = 2.0 if s == "final" else 1.0
        ax.plot(p.x_m / L0, p.h_vol_m / L0, color="k" if s == "final" else colors[i % len(colors)], lw=lw,
                label=f"t/t* = {s}" if s != "final" else f"end of run (t/t* = {r.t_end_over_tstar:.1f}, {r.end_reason})")
    ax.set_xlim(0, max(2.0, 1.15 * r.L_f_m / L0))
    ax.set_ylim(0, 1.1 * H0 / L0)
    ax.set_ylabel("h / L0")
    ax.set_title(f"{r.tag}: a = {r.a:.2f}, N = {r.N}, (L-L0)/L0 = {r.runout_over_L0:.2f} at the end of the run ({r.end_reason})", fontsize=9)
    ax.legend(fontsize=6, ncol=3, loc="upper right")
axes[-1, 0].set_xlabel("x / L0")
fig.suptitle("YADE column collapse: equivalent height h = solid volume / (dx W phi0), bins of d50", fontsize=9)
fig.tight_layout()
fig.savefig(os.path.join(args.fig, "column_profiles.png"), dpi=130)
plt.close(fig)

# --- front, back-wall height, kinetic energy ------------------------------------------------------
fig, ax = plt.subplots(1, 3, figsize=(12, 3.6))
for i, (_, r) in enumerate(sm.iterrows()):
    ts = pd.read_csv(os.path.join(args.data, f"{r.tag}_timeseries.csv"))
    L0, H0 = r.L0_m, r.H0_m
    c = colors[i % len(colors)]
    ax[0].plot(ts.t_over_tstar, (ts.L_front_m - ts.L_front_m.iloc[0]) / L0, color=c, label=f"{r.tag}")
    ax[1].plot(ts.t_over_tstar, ts.H_back_m / H0, color=c)
    ax[2].semilogy(ts.t_over_tstar, ts.kinetic_over_MgH0.clip(lower=1e-9), color=c)
    if not math.isnan(r.t99_over_tstar):
        ax[0].axvline(r.t99_over_tstar, color=c, ls=":", lw=0.8)
ax[0].set_ylabel("(L(t) - L0) / L0")
ax[1].set_ylabel("H(t) / H0 (back wall)")
ax[2].set_ylabel("E_k / (M g H0)")
for a_ in ax:
    a_.set_xlabel("t / sqrt(H0/g)")
ax[0].legend(fontsize=7)
fig.suptitle("YADE column collapse: front (dotted: t99, 99 % of the final runout), height at the back wall, "
             "kinetic energy", fontsize=9)
fig.tight_layout()
fig.savefig(os.path.join(args.fig, "column_front.png"), dpi=130)
plt.close(fig)

# --- scaling against a -------------------------------------------------------------------------
# only finished runs (at rest or at --tmax) give a runout: a run cut by --max-wall is left out
done = sm[sm.end_reason.isin(["rest", "tmax"])]
big = done.sort_values("N").groupby(done.a.round(1)).tail(1).sort_values("a")
fig, ax = plt.subplots(1, 2, figsize=(10, 4))
aa = np.logspace(math.log10(0.3), math.log10(8), 50)
ax[0].loglog(big.a, big.runout_over_L0, "ko-", label="YADE (this work)")
small = done.drop(big.index)
if big.empty:
    ax[0].text(0.05, 0.9, "no finished YADE run yet (all cut by --max-wall)", transform=ax[0].transAxes,
               fontsize=8, color="r")
if not small.empty:
    ax[0].loglog(small.a, small.runout_over_L0, "k^", mfc="none", label="YADE, smaller N")
lube = np.where(aa < 2.3, 1.2 * aa, 1.9 * aa ** (2 / 3))
ax[0].loglog(aa, lube, "b--", lw=1, label="Lube et al. 2005 as quoted: 1.2a | 1.9a^(2/3)")
for expo, lab, ls in [(0.65, "Balmforth & Kerswell narrow slot: a^0.65", "g-."),
                      (0.9, "Balmforth & Kerswell wide channel: a^0.9", "m:")]:
    ref = big.runout_over_L0.iloc[len(big) // 2] / big.a.iloc[len(big) // 2] ** expo if len(big) else 1.2
    ax[0].loglog(aa, ref * aa ** expo, ls, lw=1, label=lab + " (slope only)")
ax[0].set_xlabel("a = H0 / L0")
ax[0].set_ylabel("(L_f - L0) / L0")
ax[0].legend(fontsize=7)
ax[1].loglog(big.a, big.Hf_over_L0, "ko-", label="YADE: H_f / L0")
ax[1].loglog(big.a, big.a / big.Hf_over_L0, "rs-", label="YADE: H0 / H_f")
ref = (big.a / big.Hf_over_L0).iloc[len(big) // 2] / big.a.iloc[len(big) // 2] ** 0.5 if len(big) else 0.8
ax[1].loglog(aa, ref * aa ** 0.5, "g-.", lw=1, label="B&K narrow slot H0/h_inf ~ a^0.5 (slope only)")
ax[1].loglog(aa, np.minimum(aa, 1.0) * 0 + np.where(aa < 1, aa, np.nan), "k:", lw=1, label="H_f = H0")
ax[1].set_xlabel("a = H0 / L0")
ax[1].legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(args.fig, "column_runout_scaling.png"), dpi=130)
plt.close(fig)

if len(big) >= 2:
    la = np.log(big.a.values)
    for col in ["runout_over_L0", "Hf_over_L0"]:
        slope, icpt = np.polyfit(la, np.log(big[col].values), 1)
        print(f"fit {col} = {math.exp(icpt):.3f} a^{slope:.3f} over a = {list(big.a.round(2))}")
    h = big.a.values / big.Hf_over_L0.values
    slope, icpt = np.polyfit(la, np.log(h), 1)
    print(f"fit H0/H_f = {math.exp(icpt):.3f} a^{slope:.3f}")
