#!/usr/bin/python3
"""Scaling model of the MPM x DEM farm (docs/validation/scaling.md).

Time per MPM step on P cores with N RVEs (one RVE per material point):

    T(P, N) = t_rve * ceil-ish(N / W) / eff(N / W) * swing   slowest rank's RVE work
            + N * (s_mpm / speedup0 + s_farm + s_out)        rank 0: MPM, bookkeeping, results rows
            + 2 * alpha * R + N * b_step / beta              scatter of L + gather of records

W: cores that step RVEs; R: MPI ranks (messages per collective); eff: mean/max of the rank
loads of a METIS partition at N / W RVEs per core (measured, bench_farm partition); swing: the
slowest of the R_w ranks that step RVEs in one step, when every RVE's step cost swings with a
coefficient of variation cv independently of the others (the spread grouping), k = N / R_w RVEs
per rank: 1 + z(R_w) cv / sqrt(k), z(R) the expected largest of R standard normal draws (cv from
recorded cost traces, docs/design/farm.md "Grouping").
Efficiency E = T(1, N) / (P * T(P, N)), with T(1, N) = N * (t_rve + s_mpm + s_farm + s_out).

Reads docs/data/scaling/constants.json; prints the tables; writes docs/figures/scaling_*.png
(when matplotlib is present). Usage: tools/mpmxdem-tools scaling_model [--no-figures]
       tools/mpmxdem-tools scaling_model --doc-table   (the table of scaling.md, stdlib only)
"""
import json
import math
import pathlib
import sys

from .. import paths

ROOT = pathlib.Path(paths.ROOT)
CONSTANTS = ROOT / "docs" / "data" / "scaling" / "constants.json"
FIGURES = ROOT / "docs" / "figures"


def load():
    with open(CONSTANTS) as f:
        return json.load(f)


def balance(c, k):
    """mean/max of the rank loads at k RVEs per working core (log-linear interpolation of the
    measured METIS balances; 1 RVE per core: the cost spread alone)."""
    pts = sorted((p["rves_per_part"], p["balance"]) for p in c["metis_balance"])
    if k <= pts[0][0]:
        return pts[0][1]
    if k >= pts[-1][0]:
        return pts[-1][1]
    for (k0, e0), (k1, e1) in zip(pts, pts[1:]):
        if k0 <= k <= k1:
            w = (math.log(k) - math.log(k0)) / (math.log(k1) - math.log(k0))
            return e0 + w * (e1 - e0)
    return pts[-1][1]


def expected_max_normal(R):
    """E[max of R independent standard normal draws] (0 for R = 1), by quadrature."""
    if R <= 1:
        return 0.0
    h = 1e-3
    total = 0.0
    x = -8.0
    while x < 8.0:
        phi = math.exp(-0.5 * x * x) / math.sqrt(2.0 * math.pi)
        cdf = 0.5 * (1.0 + math.erf(x / math.sqrt(2.0)))
        total += x * R * phi * cdf ** (R - 1) * h
        x += h
    return total


_ZCACHE = {}


def swing(c, ranks_w, k_rank, cv=None):
    """1 + z(R_w) cv / sqrt(k): the slowest rank's step over the mean, from the RVEs' swings."""
    if ranks_w <= 1:
        return 1.0
    cv = c["cost_swing_cv"]["value"] if cv is None else cv
    if ranks_w not in _ZCACHE:
        _ZCACHE[ranks_w] = expected_max_normal(ranks_w)
    return 1.0 + _ZCACHE[ranks_w] * cv / math.sqrt(max(k_rank, 1.0))


def layouts(c):
    """The designs compared: how P cores are used."""
    return c["layouts"]


def step_time(c, lay, P, N, cv=None):
    """Seconds per MPM step and its parts on P cores with N RVEs for layout `lay` (cv: the RVE
    cost swings; None: the constants' central value)."""
    t = lay["threads_per_rank"]
    ranks = max(1, P // t)
    # Cores that step RVEs: all, or all but those reserved for rank 0's MPM (it owns no RVEs);
    # on small machines at most 1/8 of the cores are reserved, with a proportional MPM speed-up.
    reserved = min(lay["rank0_cores"], P // 8) if ranks > 1 else 0
    W = max(P - reserved, 1)
    speedup = max(1.0, lay["mpm_speedup"] * reserved / lay["rank0_cores"]) if reserved else 1.0
    k = N / W
    # With fewer RVEs than cores the slowest core still steps one whole RVE.
    ranks_w = max(1, W // t)
    work = c["t_rve_s"] * max(k, 1.0) / balance(c, k) * swing(c, ranks_w, N / ranks_w, cv)
    s_mpm = c["s_mpm_s"] / speedup
    rank0 = N * (s_mpm + c["s_farm_s"] + c["s_out_s"])
    if ranks > 1:
        alpha = c["alpha_s"] * (math.log2(ranks) if lay.get("tree") else ranks)
        exch = 2 * alpha + N * c["bytes_per_rve_step"] / c["beta_Bps"]
    else:
        exch = 0.0
    return work + rank0 + exch, work, rank0, exch


def efficiency(c, lay, P, N, cv=None):
    t1 = N * (c["t_rve_s"] + c["s_mpm_s"] + c["s_farm_s"] + c["s_out_s"])
    return t1 / (P * step_time(c, lay, P, N, cv)[0])


def rank0_bound(c, lay):
    """Cores beyond which rank 0's serial part per step (MPM, bookkeeping, rows and the bytes of
    the exchange) exceeds one core's RVE work (independent of N: both grow with N)."""
    s = c["s_mpm_s"] / lay["mpm_speedup"] + c["s_farm_s"] + c["s_out_s"]
    s += c["bytes_per_rve_step"] / c["beta_Bps"]
    return c["t_rve_s"] / s


def tables(c):
    Ps = [16, 64, 128, 256, 512, 1024, 2048, 4096, 10000]
    Ns = [1000, 10000, 100000]
    out = []
    for name, lay in layouts(c).items():
        out.append(f"\n## {name}: {lay['what']}")
        out.append(f"rank 0 becomes the bottleneck beyond ~{rank0_bound(c, lay):.0f} cores")
        out.append("strong scaling, parallel efficiency [%] (rows: RVEs; columns: cores)")
        out.append("N \\ P   " + "".join(f"{P:>7d}" for P in Ps))
        for N in Ns:
            out.append(f"{N:<8d}" + "".join(f"{100 * efficiency(c, lay, P, N):7.1f}" for P in Ps))
        T, w, r0, ex = step_time(c, lay, 1024, 10000)
        sw = c["cost_swing_cv"]
        lo = 100 * efficiency(c, lay, 1024, 10000, sw["high"])
        hi = 100 * efficiency(c, lay, 1024, 10000, sw["low"])
        out.append(
            f"1024 cores, 10^4 RVEs: {1e3 * T:.2f} ms/step = RVE work {1e3 * w:.2f} + rank 0 "
            f"{1e3 * r0:.2f} + exchange {1e3 * ex:.2f} ms; E = {100 * efficiency(c, lay, 1024, 10000):.1f} %"
            f" ({lo:.1f}-{hi:.1f} % for cost swings cv {sw['high']:g}-{sw['low']:g})"
        )
        out.append("weak scaling, 10 RVEs per core: E [%] = T(1 core, 10 RVEs) / T(P, 10 P)")
        out.append("P       " + "".join(f"{P:>7d}" for P in Ps))
        out.append(
            "        "
            + "".join(
                f"{100 * step_time(c, lay, 1, 10)[0] / step_time(c, lay, P, 10 * P)[0]:7.1f}"
                for P in Ps
            )
        )
    return "\n".join(out)


def figures(c):
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not found: no figures")
        return
    Ps = [int(round(10 ** (x / 8))) for x in range(8, 33)]  # 10 .. 10^4
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), sharey=True)
    for ax, N in zip(axes, [1000, 10000, 100000]):
        for name, lay in layouts(c).items():
            ax.semilogx(Ps, [100 * efficiency(c, lay, P, N) for P in Ps], label=name)
        ax.axhline(80, color="grey", ls=":", lw=1)
        ax.axvline(1024, color="grey", ls=":", lw=1)
        ax.set_title(f"strong scaling, {N:,} RVEs")
        ax.set_xlabel("cores")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("modelled parallel efficiency [%]")
    axes[0].set_ylim(0, 105)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(FIGURES / "scaling_strong.png", dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 4.2))
    for name, lay in layouts(c).items():
        ax.semilogx(
            Ps,
            [100 * step_time(c, lay, 1, 10)[0] / step_time(c, lay, P, 10 * P)[0] for P in Ps],
            label=name,
        )
    ax.axhline(80, color="grey", ls=":", lw=1)
    ax.set_xlabel("cores (10 RVEs per core)")
    ax.set_ylabel("modelled weak-scaling efficiency [%]")
    ax.set_ylim(0, 105)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(FIGURES / "scaling_weak.png", dpi=110)
    plt.close(fig)

    # Where the time of a step goes, as built, 10^4 RVEs.
    lay = layouts(c)["as built"]
    parts = [step_time(c, lay, P, 10000) for P in Ps]
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.loglog(Ps, [1e3 * p[1] for p in parts], label="slowest rank's RVE work")
    ax.loglog(Ps, [1e3 * p[2] for p in parts], label="rank 0: MPM + bookkeeping + rows")
    ax.loglog(Ps, [1e3 * max(p[3], 1e-6) for p in parts], label="scatter + gather")
    ax.set_xlabel("cores")
    ax.set_ylabel("ms per MPM step")
    ax.set_title("as built, 10,000 RVEs of 1000 spheres")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(FIGURES / "scaling_parts.png", dpi=110)
    plt.close(fig)
    print("figures: docs/figures/scaling_strong.png, scaling_weak.png, scaling_parts.png")


def swing_check(c):
    """The swing term against the balance replay of the biaxial trace (spread grouping)."""
    out = ["swing term against the replay of the 8 x 16 biaxial trace (512 RVEs, cv 0.57, spread):"]
    for R, replay in ((2, 0.991), (4, 0.976), (8, 0.925), (16, 0.854)):
        out.append(f"  {R:2d} ranks: model {1 / swing(c, R, 512 / R, 0.57):.3f}, replay {replay:.3f}")
    return "\n".join(out)


def doc_table(c):
    """The strong-scaling table of docs/validation/scaling.md (10^4 RVEs, with the cv band)."""
    Ps = [128, 256, 512, 1024, 2048, 4096]
    sw = c["cost_swing_cv"]
    rows = ["| layout | " + " | ".join(f"{P} cores" for P in Ps) + " |",
            "|---|" + "---|" * len(Ps)]
    for name, lay in layouts(c).items():
        cells = []
        for P in Ps:
            e = 100 * efficiency(c, lay, P, 10000)
            lo = 100 * efficiency(c, lay, P, 10000, sw["high"])
            hi = 100 * efficiency(c, lay, P, 10000, sw["low"])
            cells.append(f"{e:.1f} ({lo:.1f}-{hi:.1f})")
        rows.append(f"| {name} | " + " | ".join(cells) + " |")
    return "\n".join(rows)


def main():
    c = load()
    if "--doc-table" in sys.argv:
        print(doc_table(c))
        return
    print("constants:", CONSTANTS.relative_to(ROOT))
    for k in ("t_rve_s", "s_mpm_s", "s_farm_s", "s_out_s", "alpha_s", "beta_Bps"):
        print(f"  {k} = {c[k]:g}   ({c['notes'][k]})")
    sw = c["cost_swing_cv"]
    print(f"  cost_swing_cv = {sw['value']:g} ({sw['low']:g}-{sw['high']:g}: {sw['note']})")
    print(swing_check(c))
    print(tables(c))
    if "--no-figures" not in sys.argv:
        figures(c)


if __name__ == "__main__":
    main()
