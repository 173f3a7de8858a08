#!/usr/bin/python3
"""The strip footing to its limit load over layer sizes and meshes, for the Drucker-Prager
continuum (against bearing-capacity theory) and for the RVEs (docs/validation/footing.md).

Writes each run's job with tools/mpmxdem_tools/jobs/footing_make_job.py under OUT, runs it (`mpiexec -n NP
build/mpmxdem run`; a run whose results are there is kept), reads its load-settlement curve
(tools/mpmxdem_tools/analysis/footing_curves.py) and writes OUT/summary.csv, one row per run: the layer, the cell, the
bearing pressure at s/B = 0.1 and 0.2, the peak load and where it is, the limit load q_lim (the mean of q over s/B in [0.3, 0.4]; for the associated family in [0.02, 0.06])
with its drift (the mean over [0.35, 0.4] against the mean over [0.3, 0.35], in %: a load that has
levelled off drifts by a few % at most) and its spread (max - min over the window, in %), N_q = q_lim / q0, the friction angle whose Prandtl N_q that
is (tools/mpmxdem_tools/analysis/bearing_capacity.py), the wall time.

    tools/mpmxdem-tools footing_family --out docs/data/footing_frictional --family frictional
    tools/mpmxdem-tools footing_family --out docs/data/footing_associated --family associated
    tools/mpmxdem-tools footing_family --out docs/data/footing_regularised --family regularised
    tools/mpmxdem-tools footing_family --out docs/data/footing_dem --family dem --np 2
    tools/mpmxdem-tools footing_family --table docs/data/footing_frictional/summary.csv
    tools/mpmxdem-tools footing_family --out docs/data/footing_associated --family associated --windows

The frictional family takes about 40 min on one core (most of it the 3.125 mm mesh), the
regularised one (the frictional continuum with a material length l and modulus H,
[mpm.regularisation]) about 1.5 h; the RVE family hours (docs/validation/footing.md gives each
run's time).
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys
import time

from . import bearing_capacity as bc
from ..jobs import footing_make_job

from ..paths import ROOT
S_END = 0.02                  # settlement [m]: 0.4 B for the default footing (B = 50 mm)
WINDOW = (0.3, 0.4)           # s / B over which the limit load is read
# The associated continuum dilates without end (a point by the footing's edge reached ten times its
# volume at s/B = 0.29, and the load kept rising with the heave): it is made stiff (E = 500 MPa,
# E / q_lim ~ 150) so that it reaches its limit load at a small settlement, where the geometry has
# hardly changed (the small-strain setting of the theorems), and read there: over s/B in [0.02,
# 0.06], from where the load levels off to before it rises again with the heave by the footing's
# edge (on 6.25 mm cells from s/B 0.06 on: a footing becoming embedded). Mass scaling 1e3: with
# 1e4 its E_kin / W_int reached 0.13-0.22 and the load overshot by 20 %.
ASSOCIATED = dict(material="frictional", damping=0.2, dilatancy_angle=40.0, young=500e6,
                  mass_scaling=1000.0, settlement=0.003)
WINDOWS = {"associated": (0.02, 0.06)}
# Empty grid above the surface [m]: the RVEs' dilatant layer heaves beside the footing by tens of mm
# (with 50 mm a point left the grid at s/B = 0.2); the continuum, without dilatancy, much less.
# An associated flow dilates as much as it shears: its surface heaves like the RVEs'.
HEADROOM = {"dem": 0.06, "frictional": 0.025, "regularised": 0.025, "associated": 0.05}
# name: footing_make_job options (besides settlement)
# The scene's own noise: the grid's damping changed by 1e-6 of itself (the `_perturbed` runs).
PERTURBED = ("damping", "0.2000002")
FAMILIES = {
    "frictional": {
        "phi40_w0.2_h12.5": dict(width=0.2, depth=0.1, cell=0.0125),
        "phi40_w0.4_h12.5": dict(width=0.4, depth=0.2, cell=0.0125),
        "phi40_w0.8_h12.5": dict(width=0.8, depth=0.4, cell=0.0125),
        "phi40_w0.4_h25": dict(width=0.4, depth=0.2, cell=0.025),
        "phi40_w0.4_h6.25": dict(width=0.4, depth=0.2, cell=0.00625),
        "phi40_w0.4_h3.125": dict(width=0.4, depth=0.2, cell=0.003125),
        "phi40_w0.8_h6.25": dict(width=0.8, depth=0.4, cell=0.00625),
        "phi30_w0.4_h6.25": dict(width=0.4, depth=0.2, cell=0.00625, friction_angle=30.0),
    },
    # The associated Drucker-Prager continuum (psi = phi), for which Prandtl's N_q is the exact
    # limit load: what is left between them is the MPM's own error.
    "associated": {
        "phi40_psi40_w0.4_h25": dict(width=0.4, depth=0.2, cell=0.025),
        "phi40_psi40_w0.4_h12.5": dict(width=0.4, depth=0.2, cell=0.0125),
        "phi40_psi40_w0.4_h6.25": dict(width=0.4, depth=0.2, cell=0.00625),
        "phi40_psi40_w0.4_h3.125": dict(width=0.4, depth=0.2, cell=0.003125, every=100),
        # Prandtl's mechanism at 40 deg, associated, reaches about 0.4 m beyond the footing's edge:
        # the 400 mm layer's far side cuts it; the 800 mm one holds it
        "phi40_psi40_w0.8_h25": dict(width=0.8, depth=0.4, cell=0.025),
        "phi40_psi40_w0.8_h12.5": dict(width=0.8, depth=0.4, cell=0.0125),
        "phi40_psi40_w0.8_h6.25": dict(width=0.8, depth=0.4, cell=0.00625, every=100),  # results.h5 of 3 GB
        "phi30_psi30_w0.4_h12.5": dict(width=0.4, depth=0.2, cell=0.0125, friction_angle=30.0, dilatancy_angle=30.0),
        "phi30_psi30_w0.4_h6.25": dict(width=0.4, depth=0.2, cell=0.00625, friction_angle=30.0, dilatancy_angle=30.0),
        # the same settings without dilatancy, and without the cell's strain smoothing (locking)
        "phi40_psi0_w0.4_h25": dict(width=0.4, depth=0.2, cell=0.025, dilatancy_angle=0.0),
        "phi40_psi40_w0.4_h12.5_unsmoothed": dict(width=0.4, depth=0.2, cell=0.0125,
                                                  setting=("strain_smoothing", '"none"')),
        "phi40_psi40_w0.4_h6.25_unsmoothed": dict(width=0.4, depth=0.2, cell=0.00625,
                                                  setting=("strain_smoothing", '"none"')),
        "phi40_psi40_w0.4_h3.125_unsmoothed": dict(width=0.4, depth=0.2, cell=0.003125, every=100,
                                                   setting=("strain_smoothing", '"none"')),
        # the footing's node columns end at the surface: the heave beside its edge is not dragged
        "phi40_psi40_w0.4_h25_free": dict(width=0.4, depth=0.2, cell=0.025, footing_side="free"),
        "phi40_psi40_w0.4_h12.5_free": dict(width=0.4, depth=0.2, cell=0.0125, footing_side="free"),
        "phi40_psi40_w0.4_h6.25_free": dict(width=0.4, depth=0.2, cell=0.00625, footing_side="free"),
        "phi40_psi40_w0.4_h3.125_free": dict(width=0.4, depth=0.2, cell=0.003125, every=100,
                                             footing_side="free"),
        # a smooth footing (for a weightless layer Prandtl's N_q is that of the rough one)
        "phi40_psi40_w0.4_h25_smooth": dict(width=0.4, depth=0.2, cell=0.025, footing_side="free",
                                            footing_base="smooth"),
        "phi40_psi40_w0.4_h12.5_smooth": dict(width=0.4, depth=0.2, cell=0.0125, footing_side="free",
                                              footing_base="smooth"),
        "phi40_psi40_w0.4_h6.25_smooth": dict(width=0.4, depth=0.2, cell=0.00625, footing_side="free",
                                              footing_base="smooth"),
    },
    # The same continuum with a material length (mpm.regularisation): l and H, on meshes whose
    # two finest have cells of at most l / 3
    "regularised": {
        "phi40_l%g_H%g_w%g_h%g" % (l * 1e3, h / 1e6, w, c * 1e3): dict(
            width=w, depth=w / 2, cell=c, regularisation_length=l, regularisation_modulus=h,
            **({"every": 100} if c < 0.005 else {}))
        for l, h, w, c in [
            # l = 20 mm, H = 1 MPa on three meshes (the two finest with cells of at most l / 3)
            (0.02, 1e6, 0.4, 0.0125), (0.02, 1e6, 0.4, 0.00625), (0.02, 1e6, 0.4, 0.003125),
            # l = 10 mm, H = 1 MPa
            (0.01, 1e6, 0.4, 0.0125), (0.01, 1e6, 0.4, 0.00625),
            # the modulus H at l = 20 mm, and H = 5 MPa on a finer mesh and at l = 10 mm
            (0.02, 2e6, 0.4, 0.0125), (0.02, 5e6, 0.4, 0.0125), (0.02, 20e6, 0.4, 0.0125),
            (0.02, 5e6, 0.4, 0.00625), (0.01, 5e6, 0.4, 0.0125), (0.01, 5e6, 0.4, 0.00625)]
    },
    "dem": {
        "dem_w0.2_h12.5": dict(width=0.2, depth=0.1, cell=0.0125),
        "dem_w0.4_h12.5": dict(width=0.4, depth=0.2, cell=0.0125),
        "dem_w0.2_h6.25": dict(width=0.2, depth=0.1, cell=0.00625),
        # an RVE that loses every contact keeps following its cell instead of turning into a
        # stress-free disconnected material (dem.coupling.contact_loss)
        "dem_w0.2_h12.5_strained": dict(width=0.2, depth=0.1, cell=0.0125, coupling='contact_loss = "strained"'),
        # the inertia 100 times the real one instead of 1000 (3.2 times more MPM steps)
        "dem_w0.2_h12.5_ms100": dict(width=0.2, depth=0.1, cell=0.0125, mass_scaling=100.0),
        # half the time step (the CFL number): no energy created where a row of points under
        # the footing settles on a node plane
        "dem_w0.2_h12.5_cfl0.25": dict(width=0.2, depth=0.1, cell=0.0125, setting=("cfl", "0.25")),
        # the idle far field spared (dem.sparing.tolerance 1e-5): the 400 x 200 mm layer against its
        # run without sparing above, then the layer doubled again (8192 RVEs)
        "dem_w0.4_h12.5_spared": dict(width=0.4, depth=0.2, cell=0.0125, sparing=1e-5),
        "dem_w0.8_h12.5_spared": dict(width=0.8, depth=0.4, cell=0.0125, sparing=1e-5),
        # the scene's own noise: the grid's damping changed by 1e-6 of itself
        "dem_w0.4_h12.5_spared_perturbed": dict(width=0.4, depth=0.2, cell=0.0125, sparing=1e-5,
                                                setting=PERTURBED),
        "dem_w0.8_h12.5_spared_perturbed": dict(width=0.8, depth=0.4, cell=0.0125, sparing=1e-5,
                                                setting=PERTURBED),
        # and with half the time step (no numerical event: the balance closed)
        "dem_w0.4_h12.5_spared_cfl0.25": dict(width=0.4, depth=0.2, cell=0.0125, sparing=1e-5, cfl=0.25),
        # the 400 x 200 mm layer doubled in width only, and in depth only
        "dem_w0.8_d0.2_h12.5_spared_cfl0.25": dict(width=0.8, depth=0.2, cell=0.0125, sparing=1e-5, cfl=0.25),
        "dem_w0.4_d0.4_h12.5_spared_cfl0.25": dict(width=0.4, depth=0.4, cell=0.0125, sparing=1e-5, cfl=0.25),
        "dem_w0.8_d0.2_h12.5_spared_cfl0.25_perturbed": dict(width=0.8, depth=0.2, cell=0.0125, sparing=1e-5,
                                                           cfl=0.25, setting=PERTURBED),
        "dem_w0.4_d0.4_h12.5_spared_cfl0.25_perturbed": dict(width=0.4, depth=0.4, cell=0.0125, sparing=1e-5,
                                                           cfl=0.25, setting=PERTURBED),
        # the 800 x 400 mm layer doubled again (32,768 RVEs; outputs every 100 steps: the peak read
        # every 100 steps is the one read every 20 within 0.2 % on the 800 x 400 mm runs)
        "dem_w1.6_h12.5_spared": dict(width=1.6, depth=0.8, cell=0.0125, sparing=1e-5, every=100),
        "dem_w1.6_h12.5_spared_perturbed": dict(width=1.6, depth=0.8, cell=0.0125, sparing=1e-5, every=100,
                                                setting=PERTURBED),
        # the staircase's next plane held 0.75 cells ahead instead of 0.5 (the top row of points never
        # more than half a cell under a held plane): does it move the collapse at s/B 0.36?
        "dem_w0.4_h12.5_spared_cfl0.25_lead0.75": dict(width=0.4, depth=0.2, cell=0.0125, sparing=1e-5, cfl=0.25,
                                                     lead=0.75),
        "dem_w0.8_h12.5_spared_lead0.75": dict(width=0.8, depth=0.4, cell=0.0125, sparing=1e-5, lead=0.75),
        # the 400 x 200 mm layer on three meshes (cells of 25, 12.5 and 6.25 mm: the footing's
        # half-width 1, 2 and 4 cells), spared, cfl 0.25; outputs every 40 steps on the finest (its
        # steps are half as long: the same rows per settlement as every 20 on 12.5 mm)
        "dem_w0.4_h25_spared_cfl0.25": dict(width=0.4, depth=0.2, cell=0.025, sparing=1e-5, cfl=0.25, every=10),
        "dem_w0.4_h6.25_spared_cfl0.25": dict(width=0.4, depth=0.2, cell=0.00625, sparing=1e-5, cfl=0.25,
                                            every=40),
        "dem_w0.4_h6.25_spared_cfl0.25_perturbed": dict(width=0.4, depth=0.2, cell=0.00625, sparing=1e-5,
                                                      cfl=0.25, every=40, setting=PERTURBED),
        # and the 200 x 100 mm layer on 6.25 mm cells with half the time step (the run above on those
        # cells, with cfl 0.5, ended in a numerical event before its peak)
        "dem_w0.2_h6.25_spared_cfl0.25": dict(width=0.2, depth=0.1, cell=0.00625, sparing=1e-5, cfl=0.25,
                                            every=40),
    },
}
COLUMNS = ["name", "material", "phi_deg", "psi_deg", "width_m", "depth_m", "cell_m", "points", "s_end", "q_0.1_MPa",
           "q_0.2_MPa", "q_peak_MPa", "s_peak", "phi_peak_deg", "q_lim_MPa", "drift_pct", "spread_pct", "N_q",
           "phi_lim_deg", "wall_s"]


def options(family, opts):
    o = dict(footing_make_job.DEFAULTS, settlement=S_END, every=20)
    if family in ("frictional", "regularised"):
        o.update(material="frictional", damping=0.2)
    elif family == "associated":
        o.update(ASSOCIATED)
    else:
        o.update(mass_scaling=1000.0)  # with 1e4 the dilating RVE layer is not quasi-static (E_kin/W_int 0.04)
    o.update(opts)
    o["above"] = max(2, math.ceil(HEADROOM[family] / o["cell"] - 1e-9))
    extra = dict(coupling=o.pop("coupling", ""), setting=o.pop("setting", None))
    return o, extra


def mean_between(sb, q, lo, hi):
    sel = (sb >= lo - 1e-9) & (sb <= hi + 1e-9)
    if not sel.any():
        raise ValueError("no rows with s/B in [%g, %g]: did the run reach s/B = %g?" % (lo, hi, hi))
    return float(q[sel].mean())


def at(sb, q, m):
    """q at s/B = m, or None where the run did not get there."""
    k = (sb - m).abs().idxmin()
    return float(q[k]) if abs(float(sb[k]) - m) < 0.005 else None


def mpa(x):
    return "" if x is None else "%.4f" % (x / 1e6)


def reading(run, o, wall, window=WINDOW):
    from . import footing_curves  # pandas; --table needs only the standard library
    sb, q = footing_curves.curve(run)
    lo, hi = window
    mid = 0.5 * (lo + hi)
    q0 = o["pressure"]
    k = int(q.idxmax())
    nx, nz = round(o["width"] / o["cell"]), round(o["depth"] / o["cell"])
    frictional = o["material"] == "frictional"
    row = {"material": o["material"], "phi_deg": o["friction_angle"] if frictional else "",
           "psi_deg": o["dilatancy_angle"] if frictional else "",
           "width_m": o["width"], "depth_m": o["depth"], "cell_m": o["cell"], "points": 4 * nx * nz,
           "s_end": "%.3f" % float(sb.max()),
           "q_0.1_MPa": mpa(at(sb, q, 0.1)), "q_0.2_MPa": mpa(at(sb, q, 0.2)),
           "q_peak_MPa": "%.4f" % (q[k] / 1e6), "s_peak": "%.3f" % sb[k],
           "phi_peak_deg": "%.2f" % bc.effective_angle(q[k] / q0),
           "q_lim_MPa": "", "drift_pct": "", "spread_pct": "", "N_q": "", "phi_lim_deg": "", "wall_s": "%.0f" % wall}
    if sb.max() >= hi - 1e-3:
        q_lim = mean_between(sb, q, lo, hi)
        drift = 100.0 * (mean_between(sb, q, mid, hi) - mean_between(sb, q, lo, mid)) / q_lim
        sel = (sb >= lo - 1e-9) & (sb <= hi + 1e-9)
        spread = 100.0 * float(q[sel].max() - q[sel].min()) / q_lim
        row.update({"q_lim_MPa": "%.4f" % (q_lim / 1e6), "drift_pct": "%.1f" % drift,
                    "spread_pct": "%.1f" % spread, "N_q": "%.2f" % (q_lim / q0),
                    "phi_lim_deg": "%.2f" % bc.effective_angle(q_lim / q0)})
    return row


def job_text(o, extra):
    """The job footing_make_job writes, with extra["coupling"] lines added to its [dem.coupling]
    table and extra["setting"] = (key, value) replacing the value of a key it writes."""
    text = footing_make_job.job_text(**o)
    if extra["coupling"]:
        text = text.replace("[dem.coupling]\n", "[dem.coupling]\n%s\n" % extra["coupling"], 1)
    if extra["setting"]:
        key, value = extra["setting"]
        text, n = re.subn(r"(?m)^%s = .*$" % re.escape(key), "%s = %s  # set by tools/mpmxdem-tools footing_family" % (key, value),
                          text, count=1)
        if n != 1:
            raise SystemExit("footing_family: the job has no key %r to set" % key)
    return text


def run_one(out, family, name, exe, mpiexec, np_):
    o, extra = options(family, FAMILIES[family][name])
    d = os.path.join(out, name)
    job = os.path.join(out, name + ".toml")
    with open(job, "w") as f:
        f.write(job_text(o, extra))
    wall_file = os.path.join(out, name + ".wall")
    if not os.path.exists(os.path.join(d, "reactions.csv")) or not os.path.exists(wall_file):
        t0 = time.time()
        with open(os.path.join(out, name + ".log"), "w") as log:
            rc = subprocess.call([mpiexec, "-n", str(np_), "--bind-to", "none", exe, "run", job,
                                  "--out", d, "--force"], stdout=log, stderr=subprocess.STDOUT)
        if rc != 0 and not os.path.exists(os.path.join(d, "reactions.csv")):
            raise SystemExit("%s: exit %d (see %s.log)" % (name, rc, os.path.join(out, name)))
        if rc != 0:  # kept: the curve up to the failure (the table says where it ends)
            print("%s: exit %d (see %s.log); its rows are kept" % (name, rc, os.path.join(out, name)), flush=True)
        with open(wall_file, "w") as f:
            f.write("%.1f\n" % (time.time() - t0))
    wall = float(open(wall_file).read())
    return dict(name=name, **reading(d, o, wall, WINDOWS.get(family, WINDOW)))


# The associated family's load over narrower windows of s/B: where in the reading window the
# meshes agree (OUT/windows.csv, `--windows OUT`, `--windows-table OUT/windows.csv`).
SUB_WINDOWS = [(0.01, 0.02), (0.02, 0.03), (0.03, 0.04), (0.04, 0.05), (0.05, 0.06)]


def windows(out, family):
    """OUT/windows.csv: every run's mean bearing pressure [MPa] over each of SUB_WINDOWS."""
    from . import footing_curves  # pandas
    names = [n for n in FAMILIES[family] if os.path.exists(os.path.join(out, n, "reactions.csv"))]
    with open(os.path.join(out, "windows.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["name"] + ["q_%g_%g_MPa" % lh for lh in SUB_WINDOWS])
        for n in names:
            sb, q = footing_curves.curve(os.path.join(out, n))
            w.writerow([n] + ["%.3f" % (mean_between(sb, q, lo, hi) / 1e6) if sb.max() >= hi - 1e-3 else ""
                              for lo, hi in SUB_WINDOWS])


def windows_table(path):
    rows = list(csv.DictReader(open(path)))
    cols = [c for c in rows[0] if c != "name"]
    print("| run | " + " | ".join("q over s/B %s-%s [MPa]" % tuple(c.split("_")[1:3]) for c in cols) + " |")
    print("|---|" + "---|" * len(cols))
    for r in rows:
        print("| %s | %s |" % (r["name"], " | ".join(r[c] or "-" for c in cols)))


def table(summary):
    def f(x, digits=2):
        return "%.*f" % (digits, float(x)) if x else "-"
    rows = list(csv.DictReader(open(summary)))
    print("| run | layer [mm] | cell [mm] | points | q at s/B 0.1 / 0.2 [MPa] | peak q [MPa] at s/B (phi mobilised) "
          "| limit load q_lim [MPa] (drift / spread) | N_q of q_lim | phi mobilised by q_lim | wall [s] |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        lim = ("%s (%s / %s %%)" % (f(r["q_lim_MPa"]), r["drift_pct"], r["spread_pct"]), f(r["N_q"], 1),
               "%s deg" % f(r["phi_lim_deg"], 1)) if r["q_lim_MPa"] else \
            ("not reached (ends at s/B %s)" % r["s_end"], "-", "-")
        print("| %s | %g x %g | %g | %s | %s / %s | %s at %s (%s deg) | %s | %s | %s | %s |" % (
            r["name"], 1e3 * float(r["width_m"]), 1e3 * float(r["depth_m"]), 1e3 * float(r["cell_m"]),
            r["points"], f(r["q_0.1_MPa"]), f(r["q_0.2_MPa"]), f(r["q_peak_MPa"]), r["s_peak"],
            f(r["phi_peak_deg"], 1), *lim, r["wall_s"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out")
    ap.add_argument("--family", choices=sorted(FAMILIES), default="frictional")
    ap.add_argument("--only", nargs="*", default=None, help="run these names only (other rows kept)")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks per run")
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "mpmxdem"))
    ap.add_argument("--mpiexec", default="mpiexec")
    ap.add_argument("--table", metavar="SUMMARY_CSV")
    ap.add_argument("--windows", action="store_true",
                    help="write OUT/windows.csv: each run's load over narrower windows of s/B")
    ap.add_argument("--windows-table", metavar="WINDOWS_CSV")
    a = ap.parse_args()
    if a.table:
        table(a.table)
        return
    if a.windows_table:
        windows_table(a.windows_table)
        return
    if a.windows:
        if not a.out:
            ap.error("--windows needs --out")
        windows(a.out, a.family)
        return
    if not a.out:
        ap.error("--out or --table")
    os.makedirs(a.out, exist_ok=True)
    summary = os.path.join(a.out, "summary.csv")
    rows = {r["name"]: r for r in csv.DictReader(open(summary))} if os.path.exists(summary) else {}
    for r in rows.values():  # written before the dilatancy angle: the continuum had none
        r.setdefault("psi_deg", "0" if r.get("material") == "frictional" else "")
    rows = {n: r for n, r in rows.items() if set(COLUMNS) <= set(r)}  # rows of an older layout: read again
    for name in FAMILIES[a.family]:
        if a.only is not None and name not in a.only:
            continue
        rows[name] = run_one(a.out, a.family, name, a.exe, a.mpiexec, a.np)
        print(" ".join("%s=%s" % (k, rows[name][k]) for k in COLUMNS), flush=True)
        with open(summary, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=COLUMNS)
            w.writeheader()
            for n in FAMILIES[a.family]:
                if n in rows:
                    w.writerow({k: rows[n][k] for k in COLUMNS})


if __name__ == "__main__":
    sys.exit(main())
