#!/usr/bin/python3
"""The MPM x DEM column at the pure-DEM column's own size (L0 = 14.4 d50) against that column.

docs/validation/column_collapse.md, "At the grains' own size". Modes:

  --analyse RUN_DIR STEM   runs tools/mpmxdem_tools/analysis/mpm_column_collapse.py on RUN_DIR and keeps its CSVs as
                           DATA/STEM_{timeseries,profiles,summary}.csv; writes
                           DATA/STEM_mobilised.csv (the RVEs' mobilised friction angle and void
                           ratio per output row, from RUN_DIR/results.h5) and DATA/STEM_core.csv
                           (the back-lower quarter's deformation and density per output row)
                           and DATA/STEM_fronts05.csv (the fronts measured as the runout:
                           tools/mpmxdem_tools/analysis/column_fronts.py)
  --mobilised-table STEM   prints the page's table of DATA/STEM_mobilised.csv
  --transfer-table [A]     prints the page's table of the a = A column (default 2) against the
                           transfer (FLIP, its PIC share, XPIC; deposit and front), beside the grains'
  --core-table STEM...     prints the page's table of DATA/STEM_core.csv (the points that start in
                           the column's back-lower quarter: do they stay at rest, and dense?)
  --table                  prints the Markdown table of the page from DATA and the YADE summaries
  --damping-table          prints the page's table of the a = 1 columns against their damping
  --damping-aspect-table   the shipped grain-scale configuration at each aspect ratio and damping
                           against the grains' columns of the same size and damping
  --stiffness-table        prints the page's table of the columns against the grains' contact
                           modulus (300 MPa, 3 MPa) and their size (14.4, 28.8 d50)
  --figure                 writes FIG/column_grain_scale.png: final deposits and fronts against time,
                           ours over YADE's, a = 1 and a = 2
  --deposit-table          prints the page's table of the a = 2 deposits measured without a grain
                           size (runout to a height of 0.05 and 0.02 H0, centre of mass)
  --size-figure            writes FIG/column_size_a2.png: the a = 2 columns with E = 3 MPa at
                           L0 = 14.4 and 28.8 d50, MPM x DEM (one point per cell) over YADE
  --onset-table [A]        prints the page's table of the kinetic energy of the a = A columns (default
                           2) of the transfer family against the time from the release, beside the grains'
  --resolution-table       prints the page's table of the a = 1 and a = 2 columns (FLIP 0.99 with
                           XPIC(3)) on three discretisations, each quantity with its gap to the grains'
  --aspect-table           prints the page's table of the grain-scale configuration at a = 0.5, 1
                           and 2, each against the grains' column of the same size
  --aspect-figure          writes FIG/column_aspect_ratios.png: their final deposits and fronts over
                           the grains'
  --resolution-figure      writes FIG/column_resolution.png: their final deposits and fronts over YADE's
  --self-test              checks the gate's release time and the shifted time axes

Times: the MPM x DEM jobs hold their gate until the `until` of the velocity condition named "gate"
in DATA/STEM.toml, the YADE columns release theirs at t = 0; every MPM x DEM time (fronts at
1 / 2 / 3 t*, the rows picked for the tables, the figures' curves) counts from the release.

Usage: tools/mpmxdem-tools column_grain_scale [--data D] [--yade Y] [--fig F] MODE
Defaults: D = docs/data/column_collapse_mpm_grain_scale, Y = docs/data/column_collapse_yade,
F = docs/figures. Reads only CSV files (--table: the standard library; --figure: pandas and
matplotlib).
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile
import tomllib

from .. import readers
from ..paths import ROOT, tool_command

# (a, stem of the MPM x DEM run at L0 = 14.4 d50, its label), in table order
RUNS = [(1, "a1_1ppc", "1 point per cell"), (1, "a1_1ppc_damping0.2", "1 point per cell, RVE damping 0.2"),
        (1, "a1_2x2", "2 x 2 points per cell"),
        (2, "a2_1ppc", "1 point per cell"), (2, "a2_2x2", "2 x 2 points per cell")]
YADE = {1: "dense_a1_n1500_l0.05", 2: "dense_a2_n3000_l0.05"}
# the 2 x 2 jobs at L0 = 0.5 m (2500 d50), drawn for comparison: directory under docs/data, stem
LARGE = {1: ("column_collapse_mpm_2x2", "a1"), 2: ("column_collapse_mpm_2x2", "a2")}


def analyse(run, stem, data):
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run(tool_command("mpm_column_collapse") + [run, "--data", tmp, "--fig", tmp],
                       check=True, stdout=subprocess.DEVNULL)
        tags = [f[: -len("_summary.csv")] for f in os.listdir(tmp)
                if f.endswith("_summary.csv") and f != "summary.csv"]
        if len(tags) != 1:
            sys.exit(f"{run}: expected one run's CSVs, found {tags}")
        os.makedirs(data, exist_ok=True)
        for kind in ("timeseries", "profiles", "summary"):
            shutil.copy(os.path.join(tmp, f"{tags[0]}_{kind}.csv"),
                        os.path.join(data, f"{stem}_{kind}.csv"))
    summary = read_csv(os.path.join(data, f"{stem}_summary.csv"))[0]
    H0, L0 = float(summary["H0_m"]), float(summary["L0_m"])
    mobilised_series(os.path.join(run, "results.h5"), H0, os.path.join(data, f"{stem}_mobilised.csv"))
    core_series(os.path.join(run, "results.h5"), L0, H0, os.path.join(data, f"{stem}_core.csv"))
    from . import column_fronts  # it imports this module
    column_fronts.analyse(run, stem, data)
    print(f"wrote {data}/{stem}_*.csv")


def column_of_run(run):
    """(resolved job, L0 [m], H0 [m], t* = sqrt(H0 / g) [s], the gate's release [s]) of the
    column run in directory RUN: its first body's size, from RUN/job.resolved.toml and the gate
    of RUN/job.toml."""
    job = readers.job(run)
    mpm = job["mpm"]
    body = mpm["body"][0]
    L0 = body["max"][0] - body["min"][0]
    H0 = body["max"][2] - body["min"][2]
    tstar = math.sqrt(H0 / abs(mpm["gravity"][2]))
    return job, L0, H0, tstar, gate_release(os.path.join(run, "job.toml"))


def gate_release(job_path):
    """The time (s) at which a column job releases its column: the `until` of its velocity
    condition named "gate" (0 without one). The YADE columns remove their gate at t = 0, so every
    MPM x DEM time axis compared with theirs starts at the release."""
    with open(job_path, "rb") as f:
        job = tomllib.load(f)
    for bc in job.get("mpm", {}).get("velocity", []):
        if bc.get("name") == "gate" and "until" in bc:
            until = bc["until"]
            if isinstance(until, (int, float)):
                return float(until)
            value, _, unit = str(until).partition(" ")
            if unit not in SECONDS:
                sys.exit(f"{job_path}: gate until {until!r}: expected a time in s or ms")
            return float(value) * SECONDS[unit]
    return 0.0


SECONDS = {"s": 1.0, "ms": 1e-3}


def self_test():
    """gate_release and released_times on a job written here (the stored jobs say "... s")."""
    with tempfile.TemporaryDirectory() as tmp:
        job = ('[mpm]\n[[mpm.velocity]]\nname = "back_wall"\nuntil = "1 s"\n'
               '[[mpm.velocity]]\nname = "gate"\nx = 0\nuntil = "{}"\n')
        for until, want in (("20 ms", 0.02), ("0.00151789 s", 0.00151789)):
            with open(os.path.join(tmp, "c.toml"), "w") as f:
                f.write(job.format(until))
            got = gate_release(os.path.join(tmp, "c.toml"))
            assert abs(got - want) < 1e-15, (until, got)
        with open(os.path.join(tmp, "c_summary.csv"), "w") as f:
            f.write("tstar_s\n0.2\n")
        rows_ = [{"t_over_tstar": "0.1"}, {"t_over_tstar": "1.1"}]
        got = released_times(tmp, "c", rows_)  # the gate of c.toml: 0.00151789 s
        want = [0.1 - 0.00151789 / 0.2, 1.1 - 0.00151789 / 0.2]
        assert all(abs(g - w) < 1e-12 for g, w in zip(got, want)), got
        with open(os.path.join(tmp, "c.toml"), "w") as f:
            f.write('[mpm]\n[[mpm.velocity]]\nname = "wall"\nuntil = "1 s"\n')
        assert gate_release(os.path.join(tmp, "c.toml")) == 0.0  # no gate: no shift
    print("column_grain_scale self-test: gate release in s and ms, time axes shifted, no gate no shift")


def gate_shift(data, stem):
    """The gate's release time of STEM (DATA/STEM.toml) in units of its t* (DATA/STEM_summary.csv)."""
    summary = read_csv(os.path.join(data, f"{stem}_summary.csv"))[0]
    return gate_release(os.path.join(data, f"{stem}.toml")) / float(summary["tstar_s"])


def released_times(data, stem, rows_):
    """t / t* of each row (a CSV of STEM with a t_over_tstar column), counted from the gate's
    release."""
    shift = gate_shift(data, stem)
    return [float(r["t_over_tstar"]) - shift for r in rows_]


def core_series(results, L0, H0, out):
    """Per output row of a run's results.h5, the points that start in the column's back-lower
    quarter (x < L0/2, z < H0/2: behind the plane from the toe at 45 + phi/2 to the horizontal for
    any phi above 20 deg, a region the grains' column keeps at rest): their volume ratio J = V/V0
    and in-plane distortion ln(l1/l2) (l1 >= l2 the principal stretches of F in the x-z plane),
    median and 90th percentile, their RVEs' void ratio (median, 90th percentile), how many have
    moved by more than 0.1 L0 and how many RVEs have contacts, into the CSV `out`."""
    import h5py
    import numpy as np
    with h5py.File(results, "r") as f:
        t = f["time"][:]
        x = f["points/x"][:]
        F = f["points/F"][:]
        V = f["points/volume"][:]
        e = f["points/void_ratio"][:]
        z = f["points/z"][:]
    core = (x[0][:, 0] < L0 / 2) & (x[0][:, 2] < H0 / 2)
    tstar = (H0 / 9.81) ** 0.5
    with open(out, "w", newline="") as fo:
        w = csv.writer(fo)
        w.writerow(["t_over_tstar", "points", "J_median", "J_p90", "distortion_median", "distortion_p90",
                    "void_ratio_median", "void_ratio_p90", "moved", "with_contacts"])
        for i in range(len(t)):
            Fi = F[i][core].reshape(-1, 3, 3)[:, [0, 2]][:, :, [0, 2]]
            lam = np.linalg.eigvalsh(np.einsum("kji,kjl->kil", Fi, Fi))  # squared stretches, ascending
            dist = 0.5 * np.log(lam[:, 1] / lam[:, 0])
            J = V[i][core] / V[0][core]
            moved = np.linalg.norm(x[i][core] - x[0][core], axis=1) > 0.1 * L0
            w.writerow([f"{t[i] / tstar:.3f}", int(core.sum()), f"{np.median(J):.4f}",
                        f"{np.percentile(J, 90):.4f}", f"{np.median(dist):.4f}", f"{np.percentile(dist, 90):.4f}",
                        f"{np.median(e[i][core]):.4f}", f"{np.percentile(e[i][core], 90):.4f}",
                        int(moved.sum()), int((z[i][core] > 0).sum())])


def core_table(data, stems):
    """Markdown table of STEM_core.csv for each stem (label, stem) at 2, 5 and 8 t*."""
    lines = ["| run | t / t* | points moved > 0.1 L0 | volume ratio J, median / 90th percentile | "
             "distortion ln(l1/l2), median / 90th percentile | void ratio, median / 90th percentile | "
             "RVEs with contacts |", "|---|---|---|---|---|---|---|"]
    for label, stem in stems:
        rows = read_csv(os.path.join(data, f"{stem}_core.csv"))
        t = released_times(data, stem, rows)
        for tt in (2, 5, 8):
            k = min(range(len(rows)), key=lambda k: abs(t[k] - tt))
            r = rows[k]
            lines.append(f"| {label} | {t[k]:.1f} | {r['moved']} of {r['points']} | "
                         f"{float(r['J_median']):.3f} / {float(r['J_p90']):.3f} | "
                         f"{float(r['distortion_median']):.3f} / {float(r['distortion_p90']):.3f} | "
                         f"{float(r['void_ratio_median']):.2f} / {float(r['void_ratio_p90']):.2f} | "
                         f"{r['with_contacts']} of {r['points']} |")
    return "\n".join(lines)


def mobilised_series(results, H0, out):
    """Per output row of a run's results.h5: the RVEs' mobilised in-plane friction angle
    asin(radius / centre of the x-z Mohr circle, compression positive) over the RVEs with contacts
    (median, 90th percentile) and their void ratio (median, 90th percentile), into the CSV `out`."""
    import h5py
    import numpy as np
    with h5py.File(results, "r") as f:
        stress = f["rve/stress"][:]  # rows x RVEs x 9, tension positive
        e = f["rve/void_ratio"][:]
        z = f["rve/z"][:]
        t = f["time"][:]
    sxx, szz, sxz = -stress[:, :, 0], -stress[:, :, 8], -stress[:, :, 2]
    centre = (sxx + szz) / 2
    radius = np.sqrt(((sxx - szz) / 2) ** 2 + sxz ** 2)
    tstar = (H0 / 9.81) ** 0.5
    with open(out, "w", newline="") as fo:
        w = csv.writer(fo)
        w.writerow(["t_over_tstar", "rves", "rves_with_contacts", "angle_median_deg", "angle_p90_deg",
                    "void_ratio_median", "void_ratio_p90"])
        for i in range(len(t)):
            ok = (z[i] > 0) & (centre[i] > 0)
            ang = np.degrees(np.arcsin(np.clip(radius[i][ok] / centre[i][ok], 0.0, 1.0)))
            med, p90 = (np.median(ang), np.percentile(ang, 90)) if ok.any() else (float("nan"),) * 2
            w.writerow([f"{t[i] / tstar:.3f}", e.shape[1], int(ok.sum()), f"{med:.1f}", f"{p90:.1f}",
                        f"{np.median(e[i]):.4f}", f"{np.percentile(e[i], 90):.4f}"])


def mobilised_table(data, stem):
    """Markdown table of STEM_mobilised.csv at 0.15, 0.5, 1, 2, 3 and 5 t*."""
    rows = read_csv(os.path.join(data, f"{stem}_mobilised.csv"))
    lines = ["| t / t* | RVEs with contacts | mobilised friction angle, median / 90th percentile | "
             "void ratio, median / 90th percentile |", "|---|---|---|---|"]
    t = released_times(data, stem, rows)
    for tt in (0.15, 0.5, 1, 2, 3, 5):
        k = min(range(len(rows)), key=lambda k: abs(t[k] - tt))
        r = rows[k]
        lines.append(f"| {t[k]:.2f} | {r['rves_with_contacts']} of {r['rves']} | "
                     f"{float(r['angle_median_deg']):.0f} / {float(r['angle_p90_deg']):.0f} deg | "
                     f"{float(r['void_ratio_median']):.2f} / {float(r['void_ratio_p90']):.2f} |")
    return "\n".join(lines)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def interp(x, xs, ys):
    """Linear interpolation of ys(xs) at x (xs increasing; clamped at the ends)."""
    if x <= xs[0]:
        return ys[0]
    for k in range(1, len(xs)):
        if x <= xs[k]:
            w = (x - xs[k - 1]) / (xs[k] - xs[k - 1])
            return ys[k - 1] + w * (ys[k] - ys[k - 1])
    return ys[-1]


def final_profile(path):
    """(x [m], h_vol [m]) of the "final" rows of a profiles CSV (the last time when none is)."""
    rows_ = read_csv(path)
    last = [r for r in rows_ if r["t_over_tstar"] == "final"]
    if not last:
        tmax = max(float(r["t_over_tstar"]) for r in rows_)
        last = [r for r in rows_ if float(r["t_over_tstar"]) == tmax]
    return [float(r["x_m"]) for r in last], [float(r["h_vol_m"]) for r in last]


def profile_rms(ours, theirs, L0, H0, L0y, H0y):
    """RMS of (h/H0 ours - h/H0 theirs) over x/L0 in [0, the farther end of either deposit], on
    bins of 0.01 L0: the L2 distance of docs/validation/column_collapse_reference.md section 6."""
    xo, ho = [x / L0 for x in ours[0]], [h / H0 for h in ours[1]]
    xt, ht = [x / L0y for x in theirs[0]], [h / H0y for h in theirs[1]]

    def h_at(x, xs, hs):
        return 0.0 if x > xs[-1] else interp(x, xs, hs)

    end = max(max((x for x, h in zip(xo, ho) if h > 0), default=0.0),
              max((x for x, h in zip(xt, ht) if h > 0), default=0.0))
    n = max(1, int(end / 0.01))
    sq = [(h_at(k * 0.01, xo, ho) - h_at(k * 0.01, xt, ht)) ** 2 for k in range(n + 1)]
    return (sum(sq) / len(sq)) ** 0.5


def back_mass_height(profile, L0, H0):
    """Mean of h_vol / H0 over x in [0, L0/4]: the height the material at the back wall would
    have at its initial density (the mass kept there, whatever its dilation), on 100 samples."""
    xs, hs = profile
    xs = [x / L0 for x in xs]
    vals = [interp((k + 0.5) * 0.0025, xs, hs) / H0 for k in range(100)]
    return sum(vals) / len(vals)


def rows(data, yade, runs=None, refs=None):
    """The table's figures: YADE's from its summaries (refs: {a: YADE tag}, default YADE), ours
    from the CSVs of `runs` (default RUNS; stdlib only)."""
    out = {}
    for a, stem in (YADE if refs is None else refs).items():
        s = read_csv(os.path.join(yade, f"{stem}_summary.csv"))[0]
        out[(a, "yade")] = dict(front=float(s["runout_over_L0"]), cont=float(s["runout_cont_over_L0"]),
                                hf=float(s["Hf_over_H0"]), a_meas=float(s["a"]),
                                L0=float(s["L0_m"]), H0=float(s["H0_m"]),
                                prof=final_profile(os.path.join(yade, f"{stem}_profiles.csv")),
                                back=back_mass_height(
                                    final_profile(os.path.join(yade, f"{stem}_profiles.csv")),
                                    float(s["L0_m"]), float(s["H0_m"])),
                                f123=[float(s[f"front{k}_cont_over_L0"]) for k in (1, 2, 3)])
    for a, stem, _ in RUNS if runs is None else runs:
        path = os.path.join(data, f"{stem}_summary.csv")
        if not os.path.exists(path):
            continue
        s = read_csv(path)[0]
        ts = read_csv(os.path.join(data, f"{stem}_timeseries.csv"))
        L0 = float(s["L0_m"])
        t = released_times(data, stem, ts)
        L = [float(r["L_front_connected_m"]) for r in ts]
        y = out[(a, "yade")]
        prof = final_profile(os.path.join(data, f"{stem}_profiles.csv"))
        rms = profile_rms(prof, y["prof"], L0, float(s["H0_m"]), y["L0"], y["H0"])
        out[(a, stem)] = dict(front=float(s["runout_over_L0"]),
                              cont=float(s["runout_connected_over_L0"]), hf=float(s["Hf_over_H0"]),
                              f123=[(interp(k, t, L) - L0) / L0 for k in (1, 2, 3)], rms=rms,
                              back=back_mass_height(prof, L0, float(s["H0_m"])),
                              rest=float(s["Ekend_motion_over_MgH0"]), t_end=t[-1])
    return out


def table(data, yade):
    r = rows(data, yade)
    head = ("| a | column | runout, front | runout, continuous deposit | H_f/H0 (top) | "
            "h_vol/H0 at the back (x < L0/4) | continuous front at 1 / 2 / 3 t* | "
            "deposit: RMS of h_vol/H0 from the DEM's | end (t*), kinetic energy of the motion / "
            "(M g H0) |")
    lines = [head, "|---|---|---|---|---|---|---|---|---|"]

    def pct(x, ref):
        return f" ({100 * (x - ref) / ref:+.0f} %)"

    for a in (1, 2):
        y = r.get((a, "yade"))
        if y is None:
            continue
        lines.append(f"| {a} | pure DEM (YADE), L0 = 14.4 d50, a = {y['a_meas']:.3g} | "
                     f"{y['front']:.3f} | {y['cont']:.3f} | {y['hf']:.3f} | {y['back']:.2f} | "
                     + " / ".join(f"{v:.2f}" for v in y["f123"]) + " | | |")
        for aa, stem, label in RUNS:
            if aa != a or (a, stem) not in r:
                continue
            m = r[(a, stem)]
            lines.append(f"| {a} | MPM x DEM, L0 = 14.4 d50, {label} | {m['front']:.3f}{pct(m['front'], y['front'])} | "
                         f"{m['cont']:.3f}{pct(m['cont'], y['cont'])} | {m['hf']:.3f}{pct(m['hf'], y['hf'])} | "
                         f"{m['back']:.2f}{pct(m['back'], y['back'])} | "
                         + " / ".join(f"{v:.2f}" for v in m["f123"])
                         + f" | {m['rms']:.3f} | {m['t_end']:.1f}, {m['rest']:.1e} |")
    return "\n".join(lines)


# Damping (a = 1): the YADE family at 7.2 d50 (same column, collapse damping 0 / 0.05 / 0.2) and the
# MPM x DEM column at 14.4 d50 with the RVEs' damping 0 / 0.05 / 0.2
YADE_DAMPING = [("0", "dense_a1_n375_l0"), ("0.05", "dense_a1_n375_l0.05"), ("0.2", "dense_a1_n375_l0.2")]
MPM_DAMPING = [("0", "a1_1ppc_damping0"), ("0.05", "a1_1ppc"), ("0.2", "a1_1ppc_damping0.2")]


def damping_table(data, yade):
    """Markdown table: runout and fronts of the a = 1 columns against their Cundall damping."""
    lines = ["| a = 1 column | Cundall damping | runout, front | runout, continuous deposit | "
             "continuous front at 1 / 2 / 3 t* |", "|---|---|---|---|---|"]
    for damping, stem in YADE_DAMPING:
        path = os.path.join(yade, f"{stem}_summary.csv")
        if not os.path.exists(path):
            continue
        s = read_csv(path)[0]
        lines.append(f"| pure DEM (YADE), L0 = 7.2 d50, on the whole velocity | {damping} | "
                     f"{float(s['runout_over_L0']):.3f} | {float(s['runout_cont_over_L0']):.3f} | "
                     + " / ".join(f"{float(s[f'front{k}_cont_over_L0']):.2f}" for k in (1, 2, 3))
                     + " |")
    r = rows(data, yade, runs=[(1, stem, "") for _, stem in MPM_DAMPING])
    for damping, stem in MPM_DAMPING:
        if (1, stem) not in r:
            continue
        m = r[(1, stem)]
        lines.append(f"| MPM x DEM, L0 = 14.4 d50, 1 point per cell, on the RVE's fluctuations | "
                     f"{damping} | {m['front']:.3f} | {m['cont']:.3f} | "
                     + " / ".join(f"{v:.2f}" for v in m["f123"]) + " |")
    return "\n".join(lines)



# Damping of the shipped grain-scale configuration (cells of 1.8 d50, 2 x 2 points per cell, RVEs
# without contacts strained) against the grains' columns of the same size, each family starting
# from one prepared column (YADE) and one job (MPM x DEM) that differ only in the Cundall damping:
# (a, damping, YADE tag, MPM x DEM stem[, what else differs: a member of a family]); a stem None
# is a member of the grains' family, its figures without gaps
DAMPING_ASPECTS = [
    (0.5, "0", "dense_a0.5_l28.8_E3e6_l0", "a0.5_l28.8_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_damping0"),
    (0.5, "0", "dense_a0.5_l28.8_E3e6_l0",
     "a0.5_l28.8_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_damping0_g1e-6", "gravity x (1 + 1e-6)"),
    (0.5, "0", "dense_a0.5_l28.8_E3e6_l0_seed2", None, "another packing (--seed 2)"),
    (0.5, "0", "dense_a0.5_l28.8_E3e6_l0", "a0.5_l28.8_h32_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_damping0"),
    (0.5, "0.05", "dense_a0.5_l28.8_E3e6", "a0.5_l28.8_2x2_E3MPa_wallpts_flip0.99_xpic3_strained"),
    (1, "0", "dense_a1_l14.4_E3e6_l0", "a1_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_damping0"),
    (1, "0", "dense_a1_l14.4_E3e6_l0", "a1_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_damping0_g1e-6",
     "gravity x (1 + 1e-6)"),
    (1, "0", "dense_a1_l14.4_E3e6_l0_seed2", None, "another packing (--seed 2)"),
    (1, "0", "dense_a1_l14.4_E3e6_l0", "a1_h16_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_damping0"),
    (1, "0", "dense_a1_l14.4_E3e6_l0", "a1_h16_E3MPa_wallpts_flip0.99_xpic3_strained_damping0"),
    (1, "0", "dense_a1_l14.4_E3e6_l0", "a1_h32_E3MPa_wallpts_flip0.99_xpic3_strained_damping0"),
    (1, "0.05", "dense_a1_l14.4_E3e6", "a1_2x2_E3MPa_wallpts_flip0.99_xpic3_strained"),
    (2, "0", "dense_a2_l14.4_E3e6_l0", "a2_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_oneflight_damping0"),
    (2, "0", "dense_a2_l14.4_E3e6_l0",
     "a2_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_oneflight_damping0_g1e-6", "gravity x (1 + 1e-6)"),
    (2, "0", "dense_a2_l14.4_E3e6_l0",
     "a2_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_oneflight_damping0_g-1e-6", "gravity x (1 - 1e-6)"),
    (2, "0", "dense_a2_l14.4_E3e6_l0_seed2", None, "another packing (--seed 2)"),
    (2, "0", "dense_a2_l14.4_E3e6_l0", "a2_h16_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_oneflight_damping0"),
    (2, "0.05", "dense_a2_l14.4_E3e6", "a2_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_oneflight"),
    (2, "0.2", "dense_a2_l14.4_E3e6_l0.2", "a2_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_oneflight_damping0.2")]


def damping_aspect_table(data, yade):
    """Markdown table: the grain-scale configuration at each aspect ratio and Cundall damping, each
    MPM x DEM figure with its gap to the grains' column of the same size and damping (stdlib
    only)."""
    lines = [RESOLUTION_HEADER[0].replace("| a | column |", "| a | damping | column |"),
             RESOLUTION_HEADER[1] + "---|"]
    last_tag = None
    for a, damping, tag, stem, *variant in DAMPING_ASPECTS:
        if not os.path.exists(os.path.join(yade, f"{tag}_summary.csv")):
            continue
        row, ref = grains_row(yade, a, tag)
        if stem is None:  # another member of the grains' family
            lines.append(row.replace(f"| {a:g} | pure DEM (YADE), L0 = ", f"| {a:g} | {damping} | pure DEM (YADE), "
                                     + "".join(f"{v}, " for v in variant) + "L0 = ", 1))
            continue
        if tag != last_tag:  # a variant of the same damping sits under the first run's grains
            lines.append(row.replace(f"| {a:g} | pure DEM", f"| {a:g} | {damping} | pure DEM", 1))
        last_tag = tag
        label = FINER_LABELS.get(stem, ASPECT_LABELS[a]) + "".join(f", {v}" for v in variant)
        row = run_row(data, yade, a, stem, label, ref, tag)
        if row is not None:
            lines.append(row.replace(f"| {a:g} | MPM x DEM", f"| {a:g} | {damping} | MPM x DEM", 1))
    return "\n".join(lines)


ASPECT_LABELS = {0.5: "16 x 8 cells", 1: "8 x 8 cells", 2: "8 x 16 cells"}
# the same configuration on cells of half the size (0.9 d50)
FINER_LABELS = {"a1_h16_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_damping0": "16 x 16 cells",
                "a0.5_l28.8_h32_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_damping0": "32 x 16 cells",
                "a2_h16_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_oneflight_damping0": "16 x 32 cells",
                "a1_h16_E3MPa_wallpts_flip0.99_xpic3_strained_damping0": "16 x 16 cells, 1 point per cell",
                "a1_h32_E3MPa_wallpts_flip0.99_xpic3_strained_damping0": "32 x 32 cells, 1 point per cell"}


# Stiffness number and size: (a, label, E, "yade" tag or "mpm" stem); L0 = 14.4 d50 unless named
STIFFNESS = [(1, "pure DEM (YADE)", "300 MPa", "yade", "dense_a1_n1500_l0.05"),
             (1, "pure DEM (YADE)", "3 MPa", "yade", "dense_a1_l14.4_E3e6"),
             (1, "MPM x DEM, 1 point per cell", "300 MPa", "mpm", "a1_1ppc"),
             (1, "MPM x DEM, 1 point per cell", "3 MPa", "mpm", "a1_1ppc_E3MPa"),
             (1, "MPM x DEM, 2 x 2 points per cell", "3 MPa", "mpm", "a1_2x2_E3MPa"),
             (2, "pure DEM (YADE)", "300 MPa", "yade", "dense_a2_n3000_l0.05"),
             (2, "pure DEM (YADE)", "3 MPa", "yade", "dense_a2_l14.4_E3e6"),
             (2, "pure DEM (YADE), L0 = 28.8 d50", "3 MPa", "yade", "dense_a2_l28.8_E3e6"),
             (2, "MPM x DEM, 1 point per cell", "300 MPa", "mpm", "a2_1ppc"),
             (2, "MPM x DEM, 1 point per cell", "3 MPa", "mpm", "a2_1ppc_E3MPa"),
             (2, "MPM x DEM, 1 point per cell, L0 = 28.8 d50", "3 MPa", "mpm", "a2_1ppc_L28.8_E3MPa"),
             (2, "MPM x DEM, 2 x 2 points per cell", "300 MPa", "mpm", "a2_2x2"),
             (2, "MPM x DEM, 2 x 2 points per cell", "3 MPa", "mpm", "a2_2x2_E3MPa")]


def stiffness_table(data, yade):
    """Markdown table: the columns against the grains' contact modulus (and size)."""
    lines = ["| a | column (L0 = 14.4 d50 unless said) | contact modulus E | runout, front | runout, continuous "
             "deposit | H_f/H0 | h_vol/H0 at the back (x < L0/4) | continuous front at 1 / 2 / 3 t* "
             "| RVEs without contact at 0.15 / 1 t* |", "|---|---|---|---|---|---|---|---|---|"]
    r = rows(data, yade, [(a, stem, "") for a, _, _, kind, stem in STIFFNESS if kind == "mpm"])
    for a, label, modulus, kind, stem in STIFFNESS:
        if kind == "yade":
            path = os.path.join(yade, f"{stem}_summary.csv")
            if not os.path.exists(path):
                continue
            s = read_csv(path)[0]
            prof = final_profile(os.path.join(yade, f"{stem}_profiles.csv"))
            back = back_mass_height(prof, float(s["L0_m"]), float(s["H0_m"]))
            lines.append(f"| {a} | {label}, a = {float(s['a']):.3g} | {modulus} | "
                         f"{float(s['runout_over_L0']):.3f} | {float(s['runout_cont_over_L0']):.3f} | "
                         f"{float(s['Hf_over_H0']):.3f} | {back:.2f} | "
                         + " / ".join(f"{float(s[f'front{k}_cont_over_L0']):.2f}" for k in (1, 2, 3))
                         + " | |")
            continue
        if (a, stem) not in r:
            continue
        m = r[(a, stem)]
        ts = read_csv(os.path.join(data, f"{stem}_timeseries.csv"))
        summary = read_csv(os.path.join(data, f"{stem}_summary.csv"))[0]
        t = released_times(data, stem, ts)
        nc = [float(x["rves_no_contact"]) for x in ts]
        rves = summary["rves"]
        lines.append(f"| {a} | {label} | {modulus} | {m['front']:.3f} | {m['cont']:.3f} | {m['hf']:.3f} | "
                     f"{m['back']:.2f} | " + " / ".join(f"{v:.2f}" for v in m["f123"])
                     + f" | {interp(0.15, t, nc):.0f} / {interp(1.0, t, nc):.0f} of {rves} |")
    return "\n".join(lines)


def figure(data, yade, fig_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd

    def final(prof):
        last = prof[prof["t_over_tstar"].astype(str) == "final"]
        if last.empty:
            tt = pd.to_numeric(prof["t_over_tstar"], errors="coerce")
            last = prof[tt == tt.max()]
        return last

    fig, axs = plt.subplots(2, 2, figsize=(12, 7.5))
    for i, a in enumerate((1, 2)):
        ax_p, ax_f = axs[i]
        ys = os.path.join(yade, YADE[a])
        s = pd.read_csv(ys + "_summary.csv").iloc[0]
        L0, H0 = float(s["L0_m"]), float(s["H0_m"])
        last = final(pd.read_csv(ys + "_profiles.csv"))
        ax_p.plot(last["x_m"] / L0, last["h_vol_m"] / H0, color="k", lw=2.2,
                  label="pure DEM (YADE), L0 = 14.4 d50")
        ts = pd.read_csv(ys + "_timeseries.csv")
        ax_f.plot(ts["t_over_tstar"], (ts["L_cont_m"] - ts["L_cont_m"].iloc[0]) / L0, color="k",
                  lw=2.2, label="pure DEM, continuous deposit")
        for aa, stem, label in RUNS:
            base = os.path.join(data, stem)
            if aa != a or not os.path.exists(base + "_summary.csv"):
                continue
            if "damping" in stem:
                style = dict(color="tab:orange", ls=":")
            elif "2x2" in stem:
                style = dict(color="tab:red", lw=2.0)
            else:
                style = dict(color="tab:red", ls="--")
            m = pd.read_csv(base + "_summary.csv").iloc[0]
            L0m, H0m = float(m["L0_m"]), float(m["H0_m"])
            last = final(pd.read_csv(base + "_profiles.csv"))
            ax_p.plot(last["x_m"] / L0m, last["h_vol_m"] / H0m, label=f"MPM x DEM, 14.4 d50, {label}",
                      **style)
            tsm = pd.read_csv(base + "_timeseries.csv")
            ax_f.plot(tsm["t_over_tstar"] - gate_shift(data, stem),
                      (tsm["L_front_connected_m"] - L0m) / L0m,
                      label=f"MPM x DEM, 14.4 d50, {label}", **style)
        folder, stem = LARGE[a]
        base = os.path.join(os.path.dirname(data), folder, stem)
        if os.path.exists(base + "_profiles.csv"):
            last = final(pd.read_csv(base + "_profiles.csv"))
            ax_p.plot(last["x_m"] / 0.5, last["h_vol_m"] / (0.5 * a), color="tab:blue", lw=1.2,
                      label="MPM x DEM, 2500 d50 (shipped), 2 x 2")
        style_axes(ax_p, ax_f, f"a = {a}", 1 + 2.2 * a)
    save(fig, fig_dir, "column_grain_scale.png")


def style_axes(ax_p, ax_f, title, x_max):
    """Labels, limits and legends of a deposit panel (ax_p) and a front panel (ax_f)."""
    ax_p.set_xlabel("x / L0")
    ax_p.set_ylabel("deposit height (initial density) / H0")
    ax_p.set_xlim(0, x_max)
    ax_p.set_ylim(0, 1.05)
    ax_p.axvline(1.0, color="0.6", lw=0.8)
    ax_p.set_title(f"{title}: final deposit")
    ax_p.legend(fontsize=7)
    ax_f.set_xlabel("t / t* from the release")
    ax_f.set_ylabel("(L - L0) / L0, continuous deposit")
    ax_f.set_xlim(0, 10)
    ax_f.set_title(f"{title}: front")
    ax_f.legend(fontsize=7)


def save(fig, fig_dir, name):
    fig.tight_layout()
    os.makedirs(fig_dir, exist_ok=True)
    out = os.path.join(fig_dir, name)
    fig.savefig(out, dpi=100)
    print("wrote", out)


# The size pair (a = 2, E = 3 MPa): (L0 / d50, YADE tag, MPM x DEM stem)
SIZES = [(14.4, "dense_a2_l14.4_E3e6", "a2_1ppc_E3MPa"), (28.8, "dense_a2_l28.8_E3e6", "a2_1ppc_L28.8_E3MPa")]


def size_figure(data, yade, fig_dir):
    """Final deposits and continuous fronts of the a = 2 columns at two sizes, ours over YADE's."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_p, ax_f) = plt.subplots(1, 2, figsize=(12, 4.2))
    for (size, tag, stem), width in zip(SIZES, (1.2, 2.2)):
        s = read_csv(os.path.join(yade, f"{tag}_summary.csv"))[0]
        L0, H0 = float(s["L0_m"]), float(s["H0_m"])
        xs, hs = final_profile(os.path.join(yade, f"{tag}_profiles.csv"))
        ax_p.plot([x / L0 for x in xs], [h / H0 for h in hs], color="k",
                  lw=width, label=f"pure DEM (YADE), {size:g} d50")
        ts = read_csv(os.path.join(yade, f"{tag}_timeseries.csv"))
        c0 = float(ts[0]["L_cont_m"])
        ax_f.plot([float(r["t_over_tstar"]) for r in ts], [(float(r["L_cont_m"]) - c0) / L0 for r in ts],
                  color="k", lw=width, label=f"pure DEM (YADE), {size:g} d50")
        m = read_csv(os.path.join(data, f"{stem}_summary.csv"))[0]
        L0m, H0m = float(m["L0_m"]), float(m["H0_m"])
        xs, hs = final_profile(os.path.join(data, f"{stem}_profiles.csv"))
        ax_p.plot([x / L0m for x in xs], [h / H0m for h in hs],
                  color="tab:red", lw=width, ls="--", label=f"MPM x DEM, 1 point per cell, {size:g} d50")
        tsm = read_csv(os.path.join(data, f"{stem}_timeseries.csv"))
        ax_f.plot(released_times(data, stem, tsm),
                  [(float(r["L_front_connected_m"]) - L0m) / L0m for r in tsm], color="tab:red", lw=width,
                  ls="--", label=f"MPM x DEM, 1 point per cell, {size:g} d50")
    style_axes(ax_p, ax_f, "a = 2, E = 3 MPa", 3.2)
    save(fig, fig_dir, "column_size_a2.png")


# --core-table's row labels
CORE_LABELS = {"a2_1ppc_E3MPa_wallpts": "1 point per cell, FLIP", "a2_2x2_E3MPa_wallpts": "2 x 2, FLIP", "a2_2x2_E3MPa_wallpts_flip0.99": "2 x 2, FLIP 0.99",
               "a2_2x2_E3MPa_wallpts_flip0.98": "2 x 2, FLIP 0.98", "a2_2x2_E3MPa_wallpts_flip0.995": "2 x 2, FLIP 0.995",
               "a2_1ppc_E3MPa_wallpts_flip0.99": "1 point per cell, FLIP 0.99",
               "a2_2x2_E3MPa_wallpts_flip0.99_xpic3": "2 x 2, FLIP 0.99, XPIC(3)",
               "a2_2x2_E3MPa_wallpts_xpic5": "2 x 2, XPIC(5)"}


# The deposit in continuum terms: (a, label, E, "yade" tag or "mpm" stem)
DEPOSIT = [(2, "pure DEM (YADE), L0 = 14.4 d50", "300 MPa", "yade", "dense_a2_n3000_l0.05"),
           (2, "pure DEM (YADE), L0 = 14.4 d50", "3 MPa", "yade", "dense_a2_l14.4_E3e6"),
           (2, "pure DEM (YADE), L0 = 28.8 d50", "3 MPa", "yade", "dense_a2_l28.8_E3e6"),
           (2, "MPM x DEM, 1 point per cell, L0 = 14.4 d50", "3 MPa", "mpm", "a2_1ppc_E3MPa"),
           (2, "MPM x DEM, 1 point per cell, L0 = 28.8 d50", "3 MPa", "mpm", "a2_1ppc_L28.8_E3MPa"),
           (2, "MPM x DEM, 1 point per cell, L0 = 14.4 d50, wall impulse on the points", "3 MPa", "mpm",
            "a2_1ppc_E3MPa_wallpts"),
           (2, "MPM x DEM, 1 point per cell, L0 = 14.4 d50, wall impulse on the points, FLIP 0.99", "3 MPa", "mpm",
            "a2_1ppc_E3MPa_wallpts_flip0.99"),
           (2, "MPM x DEM, 2 x 2 points per cell, L0 = 14.4 d50", "3 MPa", "mpm", "a2_2x2_E3MPa"),
           (2, "MPM x DEM, 2 x 2 points per cell, L0 = 14.4 d50, wall impulse on the points", "3 MPa", "mpm",
            "a2_2x2_E3MPa_wallpts"),
           (2, "MPM x DEM, 2 x 2 points per cell, L0 = 14.4 d50, wall impulse on the points, FLIP 0.995", "3 MPa",
            "mpm", "a2_2x2_E3MPa_wallpts_flip0.995"),
           (2, "MPM x DEM, 2 x 2 points per cell, L0 = 14.4 d50, wall impulse on the points, FLIP 0.99", "3 MPa",
            "mpm", "a2_2x2_E3MPa_wallpts_flip0.99"),
           (2, "MPM x DEM, 2 x 2 points per cell, L0 = 14.4 d50, wall impulse on the points, FLIP 0.98", "3 MPa",
            "mpm", "a2_2x2_E3MPa_wallpts_flip0.98"),
           (2, "MPM x DEM, 2 x 2 points per cell, L0 = 14.4 d50", "300 MPa", "mpm", "a2_2x2")]


def deposit_end(xs, hs, level):
    """Walking from the back wall, the first x where the deposit height falls below level
    (linear between bin centres); the last bin's centre if it never does."""
    for k, (x, h) in enumerate(zip(xs, hs)):
        if h < level:
            if k == 0:
                return 0.0
            x0, h0 = xs[k - 1], hs[k - 1]
            return x0 + (x - x0) * (h0 - level) / max(h0 - h, 1e-300)
    return xs[-1]


def deposit_measures(xs, hs, L0, H0):
    """(runout where the deposit falls below 0.05 H0, the same below 0.02 H0, centre of mass x / L0,
    mass within the column's footprint x < L0 as a fraction of the whole) of a final profile."""
    total = sum(hs)
    return ((deposit_end(xs, hs, 0.05 * H0) - L0) / L0, (deposit_end(xs, hs, 0.02 * H0) - L0) / L0,
            sum(x * h for x, h in zip(xs, hs)) / total / L0, sum(h for x, h in zip(xs, hs) if x < L0) / total)


def deposit_table(data, yade):
    """Markdown table: the a = 2 deposits measured as a continuum sees them (no grain size)."""
    lines = ["| column | contact modulus E | runout, continuous deposit (to h < d50) | runout to h < 0.05 H0 "
             "| runout to h < 0.02 H0 | centre of mass x / L0 (column: 0.5) | mass left over the column's "
             "footprint (x < L0) |", "|---|---|---|---|---|---|---|"]
    for a, label, modulus, kind, stem in DEPOSIT:
        folder = yade if kind == "yade" else data
        path = os.path.join(folder, f"{stem}_summary.csv")
        if not os.path.exists(path):
            continue
        s = read_csv(path)[0]
        L0, H0 = float(s["L0_m"]), float(s["H0_m"])
        if kind == "yade":
            cont = float(s["runout_cont_over_L0"])
            label = f"{label}, a = {float(s['a']):.3g}"
        else:
            cont = rows(data, yade, [(a, stem, "")])[(a, stem)]["cont"]
        r5, r2, xc, kept = deposit_measures(*final_profile(os.path.join(folder, f"{stem}_profiles.csv")), L0, H0)
        lines.append(f"| {label} | {modulus} | {cont:.3f} | {r5:.3f} | {r2:.3f} | {xc:.3f} | {kept:.2f} |")
    return "\n".join(lines)


# The transfer family (--transfer-table [A]): (label, stem) of the column of aspect A with the wall
# impulse on the points at the grains' size and E = 3 MPa, from FLIP to a PIC share of 2 % per step
# and the XPIC updates, with 2 x 2 or one point per cell, and (a = 1) on cells half as large with
# one point per cell (the same points as 2 x 2 on the coarse grid).
TRANSFER = {
    2: [("2 x 2, FLIP", "a2_2x2_E3MPa_wallpts"),
        ("2 x 2, FLIP 0.995 (noise relaxed in 0.044 t*)", "a2_2x2_E3MPa_wallpts_flip0.995"),
        ("2 x 2, FLIP 0.99 (0.022 t*)", "a2_2x2_E3MPa_wallpts_flip0.99"),
        ("2 x 2, FLIP 0.98 (0.011 t*)", "a2_2x2_E3MPa_wallpts_flip0.98"),
        ("2 x 2, FLIP 0.99, its PIC share XPIC(3)", "a2_2x2_E3MPa_wallpts_flip0.99_xpic3"),
        ("2 x 2, XPIC(5) (flip 0)", "a2_2x2_E3MPa_wallpts_xpic5"),
        ("cells of L0/16, 1 point per cell, FLIP 0.99, XPIC(3)", "a2_h16_E3MPa_wallpts_flip0.99_xpic3"),
        ("cells of L0/16, 2 x 2, FLIP 0.99, XPIC(3)", "a2_h16_2x2_E3MPa_wallpts_flip0.99_xpic3"),
        ("1 point per cell, FLIP", "a2_1ppc_E3MPa_wallpts"),
        ("1 point per cell, FLIP 0.99", "a2_1ppc_E3MPa_wallpts_flip0.99")],
    1: [("2 x 2, FLIP", "a1_2x2_E3MPa_wallpts"),
        ("2 x 2, FLIP 0.99", "a1_2x2_E3MPa_wallpts_flip0.99"),
        ("2 x 2, FLIP 0.99, XPIC(3)", "a1_2x2_E3MPa_wallpts_flip0.99_xpic3"),
        ("2 x 2, XPIC(5) (flip 0)", "a1_2x2_E3MPa_wallpts_xpic5"),
        ("cells of L0/16, 1 point per cell, FLIP", "a1_h16_E3MPa_wallpts"),
        ("cells of L0/16, 1 point per cell, FLIP 0.99, XPIC(3)", "a1_h16_E3MPa_wallpts_flip0.99_xpic3"),
        ("cells of L0/16, 2 x 2, FLIP 0.99, XPIC(3)", "a1_h16_2x2_E3MPa_wallpts_flip0.99_xpic3")]}
TRANSFER_YADE = {2: ["dense_a2_l14.4_E3e6", "dense_a2_l28.8_E3e6"], 1: ["dense_a1_l14.4_E3e6"]}


def stored_run(data, yade, a, stem, ref=None):
    """(summary row, L0, H0, the table's figures from rows()) of the stored MPM x DEM run STEM of
    aspect a (its profile against the YADE column REF, default YADE's of that aspect); None when
    DATA has none."""
    path = os.path.join(data, f"{stem}_summary.csv")
    if not os.path.exists(path):
        return None
    s = read_csv(path)[0]
    refs = {a: ref} if ref else None
    return s, float(s["L0_m"]), float(s["H0_m"]), rows(data, yade, [(a, stem, "")], refs)[(a, stem)]


def transfer_table(data, yade, a=2):
    """Markdown table: the column's deposit and front (aspect a) against the transfer, beside the
    grains' columns of the same modulus (stdlib only)."""
    lines = ["| column | centre of mass x / L0 | mass over the footprint | runout to h < 0.05 H0 | H_f/H0 | "
             "continuous front at 1 / 2 / 3 t* |", "|---|---|---|---|---|---|"]
    for tag in TRANSFER_YADE[a]:
        s = read_csv(os.path.join(yade, f"{tag}_summary.csv"))[0]
        L0, H0 = float(s["L0_m"]), float(s["H0_m"])
        r5, _, xc, kept = deposit_measures(*final_profile(os.path.join(yade, f"{tag}_profiles.csv")), L0, H0)
        f123 = " / ".join(f"{float(s[f'front{k}_cont_over_L0']):.2f}" for k in (1, 2, 3))
        lines.append(f"| pure DEM (YADE), L0 = {float(s['L0_over_d50']):.3g} d50 | {xc:.3f} | {kept:.2f} | "
                     f"{r5:.3f} | {float(s['Hf_over_H0']):.3f} | {f123} |")
    for label, stem in TRANSFER[a]:
        run = stored_run(data, yade, a, stem)
        if run is None:
            continue
        s, L0, H0, r = run
        t_end = r["t_end"]
        f123 = " / ".join(f"{f:.2f}" if k <= t_end else "-" for k, f in zip((1, 2, 3), r["f123"]))
        if t_end < 9.5:  # a run that stopped early (exit 3): no deposit to measure
            lines.append(f"| MPM x DEM, {label}: stopped at {t_end:.1f} t* | - | - | - | - | {f123} |")
            continue
        r5, _, xc, kept = deposit_measures(*final_profile(os.path.join(data, f"{stem}_profiles.csv")), L0, H0)
        lines.append(f"| MPM x DEM, {label} | {xc:.3f} | {kept:.2f} | {r5:.3f} | "
                     f"{float(s['Hf_over_H0']):.3f} | {f123} |")
    return "\n".join(lines)


ONSET_TIMES = (0.2, 0.4, 0.6, 1.0, 1.5)


def onset_table(data, yade, a=2):
    """Markdown table: the kinetic energy of the a = A columns of the transfer family against the
    time from the release, beside the grains' of the same modulus (stdlib only)."""
    lines = ["| column | kinetic energy / (M g H0) at " + " / ".join(f"{x:g}" for x in ONSET_TIMES)
             + " t* after the release | peak: value, at t* |", "|---|---|---|"]

    def row(label, t, k):
        peak = max(range(len(k)), key=lambda i: k[i])
        lines.append(f"| {label} | " + " / ".join(f"{interp(x, t, k):.4f}" for x in ONSET_TIMES)
                     + f" | {k[peak]:.4f}, {t[peak]:.2f} |")

    for tag in TRANSFER_YADE[a]:
        s = read_csv(os.path.join(yade, f"{tag}_summary.csv"))[0]
        ts = read_csv(os.path.join(yade, f"{tag}_timeseries.csv"))
        row(f"pure DEM (YADE), L0 = {float(s['L0_over_d50']):.3g} d50",
            [float(r["t_over_tstar"]) for r in ts], [float(r["kinetic_over_MgH0"]) for r in ts])
    for label, stem in TRANSFER[a]:
        if not os.path.exists(os.path.join(data, f"{stem}_timeseries.csv")):
            continue
        ts = read_csv(os.path.join(data, f"{stem}_timeseries.csv"))
        row(f"MPM x DEM, {label}", released_times(data, stem, ts),
            [float(r["kinetic_over_MgH0"]) for r in ts])
    return "\n".join(lines)


DECAY_TIMES = (1.5, 2.0, 3.0, 4.0, 5.0)


def decay_table(data, yade, a=2):
    """Markdown table: how the a = A columns of the resolution and sub-cell families come to rest
    beside the grains': the kinetic energy of the motion and the height at the back wall against
    the time from the release (stdlib only)."""
    lines = ["| column | kinetic energy / (M g H0) at " + " / ".join(f"{x:g}" for x in DECAY_TIMES)
             + " t* after the release | H at the back wall / H0 at the same times |", "|---|---|---|"]

    def row(label, t, k, h):
        lines.append(f"| {label} | " + " / ".join(f"{interp(x, t, k):.4f}" for x in DECAY_TIMES)
                     + " | " + " / ".join(f"{interp(x, t, h):.2f}" for x in DECAY_TIMES) + " |")

    for tag in TRANSFER_YADE[a][:1]:
        s = read_csv(os.path.join(yade, f"{tag}_summary.csv"))[0]
        ts = read_csv(os.path.join(yade, f"{tag}_timeseries.csv"))
        h0 = float(ts[0]["H_back_m"])
        row(f"pure DEM (YADE), L0 = {float(s['L0_over_d50']):.3g} d50", [float(r["t_over_tstar"]) for r in ts],
            [float(r["kinetic_over_MgH0"]) for r in ts], [float(r["H_back_m"]) / h0 for r in ts])
    seen = set()
    for label, suffix in RESOLUTION + VARIANTS:
        stem = f"a{a}_{suffix}"
        if stem in seen or not os.path.exists(os.path.join(data, f"{stem}_timeseries.csv")):
            continue
        seen.add(stem)
        ts = read_csv(os.path.join(data, f"{stem}_timeseries.csv"))
        h0 = float(ts[0]["H_back_m"])
        row(f"MPM x DEM, {label.replace('the same', 'L0/8 2 x 2') if label.startswith('the same') else label}",
            released_times(data, stem, ts), [float(r["kinetic_motion_over_MgH0"]) for r in ts],
            [float(r["H_back_m"]) / h0 for r in ts])
    return "\n".join(lines)


# The resolution family (--resolution-table, --resolution-figure): the filtered transfer (FLIP 0.99,
# its PIC share XPIC(3)), the wall impulse on the points, E = 3 MPa, at three discretisations:
# (label, stem suffix after "a<A>_"), coarsest first.
RESOLUTION = [("cells of L0/8, 2 x 2 points per cell", "2x2_E3MPa_wallpts_flip0.99_xpic3"),
              ("cells of L0/16, 1 point per cell", "h16_E3MPa_wallpts_flip0.99_xpic3"),
              ("cells of L0/16, 2 x 2 points per cell", "h16_2x2_E3MPa_wallpts_flip0.99_xpic3")]


# The variants of the 2 x 2 columns (--variants-table): with and without mpm.subcell_relaxation
# or RVEs without contacts strained instead of held (docs/validation/column_collapse.md, "The points
# of a cell").
VARIANTS = [("cells of L0/8, 2 x 2 points per cell", "2x2_E3MPa_wallpts_flip0.99_xpic3"),
           ("the same, sub-cell relaxation r = 2", "2x2_E3MPa_wallpts_flip0.99_xpic3_subcell2"),
           ("the same, sub-cell relaxation r = 10", "2x2_E3MPa_wallpts_flip0.99_xpic3_subcell10"),
           ("the same, RVEs without contacts strained, not held",
            "2x2_E3MPa_wallpts_flip0.99_xpic3_strained"),
           ("the same, strained, gravity x (1 + 1e-6)", "2x2_E3MPa_wallpts_flip0.99_xpic3_strained_g1e-6"),
           ("the same, strained, free flight in one DEM step",
            "2x2_E3MPa_wallpts_flip0.99_xpic3_strained_oneflight"),
           ("the same, strained, free flight in one DEM step, gravity x (1 + 1e-6)",
            "2x2_E3MPa_wallpts_flip0.99_xpic3_strained_oneflight_g1e-6"),
           ("cells of L0/16, 2 x 2 points per cell", "h16_2x2_E3MPa_wallpts_flip0.99_xpic3"),
           ("the same, sub-cell relaxation r = 2", "h16_2x2_E3MPa_wallpts_flip0.99_xpic3_subcell2"),
           ("the same, RVEs without contacts strained, not held",
            "h16_2x2_E3MPa_wallpts_flip0.99_xpic3_strained"),
           ("the same, strained, free flight in one DEM step",
            "h16_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_oneflight")]


def gap(value, ref):
    return f"{value:.2f} ({100 * (value / ref - 1):+.0f} %)" if ref else f"{value:.2f}"


RESOLUTION_HEADER = ["| a | column | runout to h < 0.05 H0 | H_f/H0 | h_vol/H0 at the back (x < L0/4) | "
                     "continuous front at 1 t* | at 2 t* | at 3 t* | centre of mass x / L0 | "
                     "end (t*), kinetic energy / (M g H0) |", "|---|---|---|---|---|---|---|---|---|---|"]


def back_height(xs, hs, L0, H0):
    """The mean deposit height over the back quarter of the column, over H0."""
    v = [h for x, h in zip(xs, hs) if x < L0 / 4]
    return sum(v) / len(v) / H0


def grains_row(yade, a, tag):
    """(Markdown row, reference figures) of the pure-DEM column TAG of aspect a."""
    s = read_csv(os.path.join(yade, f"{tag}_summary.csv"))[0]
    L0, H0 = float(s["L0_m"]), float(s["H0_m"])
    prof = final_profile(os.path.join(yade, f"{tag}_profiles.csv"))
    r5, _, xc, _ = deposit_measures(*prof, L0, H0)
    ref = dict(r5=r5, hf=float(s["Hf_over_H0"]), xc=xc, back=back_height(*prof, L0, H0),
               f=[float(s[f"front{k}_cont_over_L0"]) for k in (1, 2, 3)])
    return (f"| {a:g} | pure DEM (YADE), L0 = {float(s['L0_over_d50']):.3g} d50 | {r5:.2f} | {ref['hf']:.2f} | "
            f"{ref['back']:.2f} | " + " | ".join(f"{f:.2f}" for f in ref["f"]) + f" | {xc:.2f} | |"), ref


def run_row(data, yade, a, stem, label, ref, tag=None):
    """The Markdown row of the stored MPM x DEM run STEM, each figure with its gap to REF's (the
    figures of the YADE column TAG); None when DATA has no such run."""
    run = stored_run(data, yade, a, stem, tag)
    if run is None:
        return None
    m, Lm, Hm, r = run
    prof = final_profile(os.path.join(data, f"{stem}_profiles.csv"))
    m5, _, mxc, _ = deposit_measures(*prof, Lm, Hm)
    return (f"| {a:g} | MPM x DEM, {label} | {gap(m5, ref['r5'])} | {gap(float(m['Hf_over_H0']), ref['hf'])} | "
            f"{gap(back_height(*prof, Lm, Hm), ref['back'])} | "
            + " | ".join(gap(f, fr) for f, fr in zip(r["f123"], ref["f"]))
            + f" | {gap(mxc, ref['xc'])} | {r['t_end']:.1f}, {float(m['Ekend_motion_over_MgH0']):.1e} |")


def resolution_table(data, yade, family=None):
    """Markdown table: the quantities the column must match (runout, H_f, fronts at 1 / 2 / 3 t*)
    against the discretisation (or another family of (label, stem suffix) runs), each with its
    gap to the grains' column of the same modulus at L0 = 14.4 d50 (stdlib only)."""
    family = RESOLUTION if family is None else family
    lines = list(RESOLUTION_HEADER)
    for a in (1, 2):
        row, ref = grains_row(yade, a, TRANSFER_YADE[a][0])
        lines.append(row)
        for label, suffix in family:
            row = run_row(data, yade, a, f"a{a}_{suffix}", label, ref)
            if row is not None:
                lines.append(row)
    return "\n".join(lines)


# The configuration of the shipped grain-scale jobs (cells of 1.8 d50, 2 x 2 points per cell, FLIP
# 0.99 with XPIC(3), RVEs without contacts strained) at each aspect ratio, against the pure-DEM
# column of the same size (--aspect-table): (a, YADE tag, MPM x DEM stem, label).
ASPECTS = [(0.5, "dense_a0.5_l28.8_E3e6", "a0.5_l28.8_2x2_E3MPa_wallpts_flip0.99_xpic3_strained",
            "L0 = 28.8 d50, 16 x 8 cells, 2 x 2"),
           (1, "dense_a1_l14.4_E3e6", "a1_2x2_E3MPa_wallpts_flip0.99_xpic3_strained",
            "L0 = 14.4 d50, 8 x 8 cells, 2 x 2 (jobs/column_collapse_a1_grain_scale.toml)"),
           (2, "dense_a2_l14.4_E3e6", "a2_2x2_E3MPa_wallpts_flip0.99_xpic3_strained_oneflight",
            "L0 = 14.4 d50, 8 x 16 cells, 2 x 2 (jobs/column_collapse_a2_grain_scale.toml)")]


def aspect_table(data, yade):
    """Markdown table: the grain-scale configuration at a = 0.5, 1 and 2 against the grains'
    columns of the same size, each figure with its gap (stdlib only)."""
    lines = list(RESOLUTION_HEADER)
    for a, tag, stem, label in ASPECTS:
        if not os.path.exists(os.path.join(yade, f"{tag}_summary.csv")):
            continue
        row, ref = grains_row(yade, a, tag)
        lines.append(row)
        row = run_row(data, yade, a, stem, label, ref, tag)
        if row is not None:
            lines.append(row)
    return "\n".join(lines)


def deposit_panels(ax_p, ax_f, data, yade, tag, runs, title, x_max):
    """The final deposit (ax_p) and the continuous front against time (ax_f) of the YADE column
    TAG and of the stored MPM x DEM runs [(label, stem, colour)] over it."""
    s = read_csv(os.path.join(yade, f"{tag}_summary.csv"))[0]
    L0, H0 = float(s["L0_m"]), float(s["H0_m"])
    label = f"pure DEM (YADE), {float(s['L0_over_d50']):.3g} d50"
    xs, hs = final_profile(os.path.join(yade, f"{tag}_profiles.csv"))
    ax_p.plot([x / L0 for x in xs], [h / H0 for h in hs], color="k", lw=2, label=label)
    ts = read_csv(os.path.join(yade, f"{tag}_timeseries.csv"))
    c0 = float(ts[0]["L_cont_m"])
    ax_f.plot([float(r["t_over_tstar"]) for r in ts], [(float(r["L_cont_m"]) - c0) / L0 for r in ts],
              color="k", lw=2, label=label)
    for label, stem, color in runs:
        if not os.path.exists(os.path.join(data, f"{stem}_summary.csv")):
            continue
        m = read_csv(os.path.join(data, f"{stem}_summary.csv"))[0]
        Lm, Hm = float(m["L0_m"]), float(m["H0_m"])
        xs, hs = final_profile(os.path.join(data, f"{stem}_profiles.csv"))
        ax_p.plot([x / Lm for x in xs], [h / Hm for h in hs], color=color, ls="--", label=f"MPM x DEM, {label}")
        tsm = read_csv(os.path.join(data, f"{stem}_timeseries.csv"))
        ax_f.plot(released_times(data, stem, tsm), [(float(r["L_front_connected_m"]) - Lm) / Lm for r in tsm],
                  color=color, ls="--", label=f"MPM x DEM, {label}")
    style_axes(ax_p, ax_f, title, x_max)


def resolution_figure(data, yade, fig_dir):
    """Final deposits and continuous fronts of the resolution family over the grains', a = 1, 2."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(2, 2, figsize=(12, 8))
    for row, a in enumerate((1, 2)):
        runs = [(label, f"a{a}_{suffix}", color)
                for (label, suffix), color in zip(RESOLUTION, ("tab:blue", "tab:orange", "tab:red"))]
        deposit_panels(*axs[row], data, yade, TRANSFER_YADE[a][0], runs,
                       f"a = {a}, E = 3 MPa, FLIP 0.99 + XPIC(3)", 1.5 if a == 1 else 2.5)
    save(fig, fig_dir, "column_resolution.png")


def aspect_figure(data, yade, fig_dir):
    """Final deposits and continuous fronts of the grain-scale configuration at a = 0.5, 1 and 2
    over the grains' columns of the same size (FIG/column_aspect_ratios.png)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(len(ASPECTS), 2, figsize=(12, 4 * len(ASPECTS)))
    for row, (a, tag, stem, label) in enumerate(ASPECTS):
        deposit_panels(*axs[row], data, yade, tag, [(label.split(" (")[0], stem, "tab:red")],
                       f"a = {a:g}", {0.5: 1.5, 1: 2.0, 2: 2.5}[a])
    save(fig, fig_dir, "column_aspect_ratios.png")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", default=os.path.join(ROOT, "docs", "data",
                                                   "column_collapse_mpm_grain_scale"))
    ap.add_argument("--yade", default=os.path.join(ROOT, "docs", "data", "column_collapse_yade"))
    ap.add_argument("--fig", default=os.path.join(ROOT, "docs", "figures"))
    ap.add_argument("--analyse", nargs=2, metavar=("RUN_DIR", "STEM"))
    ap.add_argument("--table", action="store_true")
    ap.add_argument("--damping-table", action="store_true")
    ap.add_argument("--damping-aspect-table", action="store_true")
    ap.add_argument("--stiffness-table", action="store_true")
    ap.add_argument("--figure", action="store_true")
    ap.add_argument("--size-figure", action="store_true")
    ap.add_argument("--deposit-table", action="store_true")
    ap.add_argument("--mobilised-table", metavar="STEM")
    ap.add_argument("--core-table", nargs="+", metavar="STEM")
    ap.add_argument("--transfer-table", nargs="?", type=int, const=2, choices=(1, 2), metavar="A")
    ap.add_argument("--onset-table", nargs="?", type=int, const=2, choices=(1, 2), metavar="A")
    ap.add_argument("--resolution-table", action="store_true")
    ap.add_argument("--aspect-table", action="store_true")
    ap.add_argument("--aspect-figure", action="store_true")
    ap.add_argument("--variants-table", action="store_true")
    ap.add_argument("--decay-table", action="store_true")
    ap.add_argument("--resolution-figure", action="store_true")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    if args.self_test:
        self_test()
        return
    if args.analyse:
        analyse(args.analyse[0], args.analyse[1], args.data)
    if args.table:
        print(table(args.data, args.yade))
    if args.damping_table:
        print(damping_table(args.data, args.yade))
    if args.damping_aspect_table:
        print(damping_aspect_table(args.data, args.yade))
    if args.stiffness_table:
        print(stiffness_table(args.data, args.yade))
    if args.figure:
        figure(args.data, args.yade, args.fig)
    if args.size_figure:
        size_figure(args.data, args.yade, args.fig)
    if args.deposit_table:
        print(deposit_table(args.data, args.yade))
    if args.mobilised_table:
        print(mobilised_table(args.data, args.mobilised_table))
    if args.core_table:
        print(core_table(args.data, [(CORE_LABELS.get(s, s), s) for s in args.core_table]))
    if args.transfer_table:
        print(transfer_table(args.data, args.yade, args.transfer_table))
    if args.onset_table:
        print(onset_table(args.data, args.yade, args.onset_table))
    if args.resolution_table:
        print(resolution_table(args.data, args.yade))
    if args.aspect_table:
        print(aspect_table(args.data, args.yade))
    if args.aspect_figure:
        aspect_figure(args.data, args.yade, args.fig)
    if args.variants_table:
        print(resolution_table(args.data, args.yade, VARIANTS))
    if args.decay_table:
        print(decay_table(args.data, args.yade))
    if args.resolution_figure:
        resolution_figure(args.data, args.yade, args.fig)
    if not (args.analyse or args.table or args.damping_table or args.damping_aspect_table or args.stiffness_table or args.figure
            or args.size_figure or args.deposit_table or args.mobilised_table or args.core_table
            or args.transfer_table or args.onset_table or args.resolution_table or args.aspect_table
            or args.aspect_figure or args.variants_table
            or args.decay_table or args.resolution_figure):
        ap.error("one of --analyse, --table, --damping-table, --stiffness-table, --deposit-table, --figure, "
                 "--size-figure")


if __name__ == "__main__":
    main()
