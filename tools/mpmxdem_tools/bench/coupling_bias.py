#!/usr/bin/python3
"""Is a [dem.coupling] option a bias or noise on a sensitive scene? (docs/validation/speed.md)

A single run of an option against a single reference says little where the scene's response is
chaotic (the biaxial's softening branch moves by several per cent under a 1e-6 perturbation of
the platen speed). This runs two families, the reference variant and the option, each on the
same K perturbations of the scene (the platen or footing speed scaled by 1 + k 1e-6, k in
--offsets), and compares them per strain:
  - the spread within each family (the sample standard deviation over its K runs),
  - the difference of the family means, and Welch's t of that difference (|t| > ~2.5 at
    K = 5 is a difference the noise does not explain),
summarised over two ranges of the reference family's mean curve: biaxial, the stress ratio before
and after its peak; footing, the reaction up to 0.7 of the settlement and after (values relative
to the curve's largest).

  tools/mpmxdem-tools coupling_bias --out OUT [--scene biaxial] \
      [--variants 'end_forces = "separate";end_forces = "carried"'] [--offsets 0,3,-3,6,-4.5]
      [--reuse]
      [--keep-going]

A variant's parts joined by '+' are [dem.coupling] lines, or 'numerics.KEY = x' ([dem.numerics]),
'mpm.KEY = x' ([mpm]), 'sparing.tolerance = x' (tools/mpmxdem_tools/bench/bench_coupling.py). --keep-going reports a
failed run (exit 3, say) and leaves it out: the collapse families of docs/validation/speed.md
("Defaults"), e.g. --scene collapse --keep-going --variants 'end_forces = "separate"+
numerics.verlet_skin_min = 0;end_forces = "carried"+numerics.verlet_skin_min = 0.03' (add
'+mpm.wall_impulse = "points"' to both for the "points" families).

Runs go through tools/mpmxdem_tools/bench/bench_coupling.py's run() (2 ranks x 1 thread, niced); the runs of a
family alternate with the other's. Writes coupling_bias.csv (per strain: both means, both
standard deviations, t) and prints the summary. Scenes: biaxial (the stress ratio sigma_a /
sigma_r of tools/mpmxdem_tools/analysis/biaxial_analysis.py), footing (the footing's reaction against its settlement),
collapse (gravity perturbed; the runout of all points and of the connected deposit and H_f / H0:
scalars, each family's mean and standard deviation and Welch's t).
"""
import argparse
import os
import sys

import numpy as np

from . import bench_coupling as bc  # noqa: E402
from . import bench_sparing as bs  # noqa: E402

# The scene's loading speed (perturbed), the curve compared and the split of its two ranges.
SPEED = {"biaxial": ('z = "-3.0 mm/s"', "-3.0"), "footing": ('z = "-1 mm/s"', "-1"),
         "collapse": ('"-9.81 m/s^2"', "-9.81")}  # the collapse: gravity


def curve(kind, m):
    """(x, y) of a run: biaxial: axial strain, stress ratio; footing: settlement, reaction."""
    if kind == "biaxial":
        return m["eps"], m["ratio"]
    return np.abs(m["settlement"]), np.abs(m["reaction"])


def split(kind, x, y):
    """Index that ends the first range: the peak (biaxial) or 0.7 of the settlement (footing)."""
    if kind == "biaxial":
        return int(np.argmax(y))
    return int(np.searchsorted(x, 0.7 * x.max()))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(bs.ROOT, "build", "mpmxdem"))
    ap.add_argument("--out", required=True)
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--scene", default="biaxial", choices=sorted(SPEED))
    # the older RVE step's end forces against the default's (a variant naming only the default's
    # own values would compare the default with itself)
    ap.add_argument("--variants", default='end_forces = "separate";end_forces = "carried"')
    ap.add_argument("--offsets", default="0,3,-3,6,-4.5",
                    help="perturbations k: the speed times 1 + k 1e-6 (0: the job's own)")
    ap.add_argument("--reuse", action="store_true")
    ap.add_argument("--keep-going", action="store_true",
                    help="a failed run (e.g. exit 3) is reported and left out of the statistics")
    args = ap.parse_args()
    args.exe = os.path.abspath(args.exe)
    # what bench_coupling.run() reads of its arguments
    args.tolerance, args.max_spared = 0.0, 20
    os.makedirs(args.out, exist_ok=True)
    variants = [v.strip() for v in args.variants.split(";")]
    assert len(variants) == 2, "two variants: the reference and the option"
    old, speed = SPEED[args.scene]
    offsets = [float(x) for x in args.offsets.split(",")]
    kind = bs.SCENES[args.scene][2]
    curves = {v: [] for v in variants}
    for k in offsets:
        new = old.replace(speed, "%.10g" % (float(speed) * (1.0 + k * 1e-6)))
        assert k == 0 or new != old, (old, speed)
        pert = False if k == 0 else "%s=>%s" % (old, new)
        for v in variants:
            r = bc.run(args, args.scene, v, 0, pert)
            if r is None:
                print("%s [%s] k %+g: FAILED" % (args.scene, v, k), flush=True)
                continue
            out, wall, rve, work = r
            m = bs.measures(out, kind, work)
            curves[v].append(m)
            print("%s [%s] k %+g: wall %.1f s, %d DEM steps, %s" % (
                args.scene, v, k, wall, work["dem_steps"],
                "runout %.4f (connected %.4f), H_f/H0 %.4f" % (m["runout_all"], m["runout"], m["height"])
                if kind == "collapse" else "peak %.6g" % curve(kind, m)[1].max()), flush=True)
    if min(len(curves[v]) for v in variants) < 2:
        sys.exit("fewer than two runs of a variant completed: no statistics")
    if kind == "collapse":  # scalar measures: each family's mean and sd, Welch's t
        print("reference: %s (%d runs); option: %s (%d runs); perturbations k = %s" % (
            variants[0], len(curves[variants[0]]), variants[1], len(curves[variants[1]]),
            args.offsets))
        print("| measure | reference: mean, sd | option: mean, sd | difference | Welch's t |")
        print("|---|---|---|---|---|")
        for key, name in (("runout_all", "runout (L_f - L0) / L0, all points"),
                          ("runout", "runout, connected deposit"), ("height", "H_f / H0")):
            a = np.array([m[key] for m in curves[variants[0]]])
            b = np.array([m[key] for m in curves[variants[1]]])
            se = np.sqrt(a.var(ddof=1) / len(a) + b.var(ddof=1) / len(b))
            print("| %s | %.4f, %.4f | %.4f, %.4f | %+.4f | %.2f |" % (
                name, a.mean(), a.std(ddof=1), b.mean(), b.std(ddof=1), b.mean() - a.mean(),
                (b.mean() - a.mean()) / se if se > 0 else 0.0))
        return
    eps = curve(kind, curves[variants[0]][0])[0]
    fam = {v: np.array([np.interp(eps, *curve(kind, m)) for m in curves[v]]) for v in variants}
    mean = {v: fam[v].mean(axis=0) for v in variants}
    sd = {v: fam[v].std(axis=0, ddof=1) for v in variants}
    n = len(offsets)
    diff = mean[variants[1]] - mean[variants[0]]
    se = np.sqrt(sd[variants[0]] ** 2 / len(fam[variants[0]]) + sd[variants[1]] ** 2 / len(fam[variants[1]]))
    t = np.where(se > 0, diff / np.where(se > 0, se, 1.0), 0.0)
    kpk = split(kind, eps, mean[variants[0]])
    peak = mean[variants[0]].max()
    with open(os.path.join(args.out, "coupling_bias.csv"), "w") as f:
        f.write("%s,mean_ref,sd_ref,mean_opt,sd_opt,t\n" % ("eps" if kind == "biaxial" else "settlement"))
        for r in zip(eps, mean[variants[0]], sd[variants[0]], mean[variants[1]], sd[variants[1]], t):
            f.write(",".join("%.8g" % x for x in r) + "\n")
    print("reference: %s; option: %s; %d perturbations each (k = %s)" % (
        variants[0], variants[1], n, args.offsets))
    print("| range | spread of the reference (sd / peak): median, max | of the option | "
          "mean difference (/ peak): median, max abs | mean over the range (signed) | "
          "|t|: median, max | strains with |t| > 2.5 |")
    print("|---|---|---|---|---|---|---|")
    names = ("pre-peak", "post-peak") if kind == "biaxial" else ("to 0.7 of the settlement", "after")
    for name, sl in zip(names, (slice(1, kpk + 1), slice(kpk, None))):
        a = lambda x: np.abs(x[sl]) / peak  # noqa: E731
        print("| %s | %.2f %%, %.2f %% | %.2f %%, %.2f %% | %.2f %%, %.2f %% | %+.2f %% | %.1f, %.1f | %.0f %% |" % (
            name, 100 * np.median(a(sd[variants[0]])), 100 * a(sd[variants[0]]).max(),
            100 * np.median(a(sd[variants[1]])), 100 * a(sd[variants[1]]).max(),
            100 * np.median(a(diff)), 100 * a(diff).max(), 100 * diff[sl].mean() / peak,
            np.median(np.abs(t[sl])), np.abs(t[sl]).max(), 100 * np.mean(np.abs(t[sl]) > 2.5)))


if __name__ == "__main__":
    main()
