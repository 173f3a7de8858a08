#!/usr/bin/python3
"""Stress ratio q/p of a pure-DEM drained triaxial against YADE's on the same packing.

Usage: tools/mpmxdem-tools dem_against_yade OURS.csv YADE.csv [--strain 0.25] [--markdown]

OURS.csv is the dem_series.csv of `mpmxdem dem` (or the output of triax_dem), YADE.csv a YADE
series (tests/data/dem/yade_triax_*.csv, docs/data/yade_hertz_mindlin/); both have the columns
eps_a, eps_v, sig_a, sig_r (logarithmic strains, compression positive; stresses compression
positive). Prints the peak q/p of each (q = sig_a - sig_r, p = (sig_a + 2 sig_r) / 3) and where
it is, their relative difference, q/p at 5, 10, 15, 20 and 25 %, the RMS of the relative q/p
difference over YADE's rows from 0.2 % (q/p ~ 0 before) to --strain, eps_v at the end and the
largest lateral-stress error of each after 0.05 % strain. Standard library only.
"""
import argparse
import csv
import math


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    eps = [float(r["eps_a"]) for r in rows]
    epsv = [float(r["eps_v"]) for r in rows]
    sa = [float(r["sig_a"]) for r in rows]
    sr = [float(r["sig_r"]) for r in rows]
    qp = [(a - b) / ((a + 2 * b) / 3) for a, b in zip(sa, sr)]
    # The lateral stresses one by one (sxx, syy: tension positive in both files) where given.
    lat = ([(-float(r["sxx"]), -float(r["syy"])) for r in rows] if "sxx" in rows[0]
           else [(b, b) for b in sr])
    return {"eps": eps, "epsv": epsv, "qp": qp, "lat": lat}


def interp(x, xs, ys):
    if x <= xs[0]:
        return ys[0]
    for k in range(1, len(xs)):
        if xs[k] >= x:
            t = (x - xs[k - 1]) / (xs[k] - xs[k - 1]) if xs[k] > xs[k - 1] else 0.0
            return ys[k - 1] + t * (ys[k] - ys[k - 1])
    return ys[-1]


def peak(s, strain):
    best = max((q, e) for q, e in zip(s["qp"], s["eps"]) if e <= strain)
    return best


def lateral(s, p0):
    return max(max(abs(x - p0), abs(y - p0)) / p0 for (x, y), e in zip(s["lat"], s["eps"]) if e > 5e-4)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("ours")
    ap.add_argument("yade")
    ap.add_argument("--strain", type=float, default=0.25)
    ap.add_argument("--pressure", type=float, default=1e5, help="confining pressure [Pa]")
    ap.add_argument("--markdown", action="store_true", help="the table of the docs")
    a = ap.parse_args()
    ours, yade = read(a.ours), read(a.yade)
    end = min(a.strain, ours["eps"][-1], yade["eps"][-1])
    (po, eo), (py, ey) = peak(ours, end), peak(yade, end)
    grid = [e for e in yade["eps"] if 2e-3 <= e <= end]
    rel = [(interp(e, ours["eps"], ours["qp"]) - interp(e, yade["eps"], yade["qp"]))
           / interp(e, yade["eps"], yade["qp"]) for e in grid]
    rms = math.sqrt(sum(r * r for r in rel) / len(rel))
    rows = [("peak q/p (at eps_a)", f"{py:.3f} ({100 * ey:.2f} %)", f"{po:.3f} ({100 * eo:.2f} %)",
             f"{100 * (po / py - 1):+.1f} %")]
    for s in (0.05, 0.10, 0.15, 0.20, 0.25):
        if s <= end + 1e-9:
            qy, qo = interp(s, yade["eps"], yade["qp"]), interp(s, ours["eps"], ours["qp"])
            rows.append((f"q/p at {100 * s:.0f} %", f"{qy:.3f}", f"{qo:.3f}", f"{100 * (qo / qy - 1):+.1f} %"))
    rows.append((f"RMS of the relative q/p difference, 0.2-{100 * end:.0f} %", "", "", f"{100 * rms:.1f} %"))
    vy, vo = interp(end, yade["eps"], yade["epsv"]), interp(end, ours["eps"], ours["epsv"])
    rows.append((f"eps_v at {100 * end:.0f} % (compression positive)", f"{100 * vy:.2f} %", f"{100 * vo:.2f} %",
                 f"{100 * (vo - vy):+.2f} % of strain"))
    rows.append(("largest lateral-stress error (sxx, syy) after 0.05 %", f"{100 * lateral(yade, a.pressure):.2f} %",
                 f"{100 * lateral(ours, a.pressure):.2f} %", ""))
    if a.markdown:
        print("| quantity | YADE | mpmxdem | difference |")
        print("|---|---|---|---|")
        for r in rows:
            print("| " + " | ".join(r) + " |")
    else:
        for r in rows:
            print(f"{r[0]:55s} YADE {r[1]:>16s}  mpmxdem {r[2]:>16s}  {r[3]}")


if __name__ == "__main__":
    main()
