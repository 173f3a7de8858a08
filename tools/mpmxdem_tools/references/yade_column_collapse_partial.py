#!/usr/bin/python3
"""Summary row of a YADE column collapse (tools/mpmxdem_tools/references/yade_column_collapse.py) that is still running or
was stopped without writing its own: the same columns and definitions as the script's summary,
from the run's log ("deposited:" line: H0, a, phi0, t*; the set-up line: N, L0, W, damping) and
its time series so far, with end_reason = "partial_<UTC time of the copy>", and t99 / t_ek1pc left
NaN (not at rest).

  tools/mpmxdem-tools yade_column_collapse_partial LOG TIMESERIES_CSV OUT_SUMMARY_CSV
"""
import argparse
import csv
import re
import sys
import time

G = 9.81


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("log", help="the YADE run's log")
    ap.add_argument("timeseries", help="its time series so far (CSV)")
    ap.add_argument("out", help="the summary row to write (CSV)")
    args = ap.parse_args()
    log, ts_path, out = args.log, args.timeseries, args.out
    text = open(log).read()
    tag = re.search(r"^\[([^\]]+)\]", text, re.M).group(1)
    m = re.search(r"deposited: H0=([0-9.e+-]+) m, a=([0-9.]+), phi0=([0-9.]+), t\*=([0-9.e+-]+) s, "
                  r"prep steps=(\d+)", text)
    H0, a, phi0, tstar, prep = float(m[1]), float(m[2]), float(m[3]), float(m[4]), int(m[5])
    # The set-up line ("N=386 ... L0=1.44e-03 ... (W/d50=5) ...; ..., damping 0.05, ..."), where the
    # log has one; else the tag's N, L0 from a (the log rounds a to 3 digits: within 0.1 %) and the
    # legacy set-up's W = 4 d50, damping 0.2.
    setup = re.search(r"\] N=(\d+) .*L0=([0-9.e+-]+) .*\(W/d50=([0-9.]+)\).*, damping ([0-9.e+-]+)", text)
    if setup:
        n, L0, width, damping = int(setup[1]), float(setup[2]), float(setup[3]), float(setup[4])
    else:
        n, L0, width, damping = int(re.search(r"_n(\d+)", tag)[1]), H0 / a, 4.0, 0.2
    rows = list(csv.DictReader(open(ts_path)))
    first, last = rows[0], rows[-1]
    t = float(last["t_s"])
    Lf = L0 + float(last["L_front_m"]) - float(first["L_front_m"])
    Hf = float(last["H_back_m"])
    steps = int(last["step"])
    with open(out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["tag", "a", "N", "W_over_d50", "damping", "d50_m", "L0_m", "H0_m", "phi0", "tstar_s", "L_f_m",
                    "H_f_m", "runout_over_L0", "Hf_over_L0", "Hf_over_H0", "t99_over_tstar", "t_ek1pc_over_tstar",
                    "t_end_over_tstar", "end_reason", "Ek_end_over_MgH0", "prep_steps", "collapse_steps",
                    "mean_dt_s", "wall_s"])
        w.writerow([tag, f"{a:.4f}", n, width, damping, 0.0002, f"{L0:.5e}", f"{H0:.5e}", f"{phi0:.4f}", f"{tstar:.5e}",
                    f"{Lf:.5e}", f"{Hf:.5e}", f"{(Lf - L0) / L0:.4f}", f"{Hf / L0:.4f}", f"{Hf / H0:.4f}", "nan", "nan",
                    f"{t / tstar:.3f}", "partial_" + time.strftime("%H%MZ", time.gmtime()),
                    f"{float(last['kinetic_over_MgH0']):.3e}", prep, steps, f"{t / max(steps, 1):.4e}",
                    f"{float(last['wall_s']):.0f}"])
    print(f"{out}: {tag} to t/t* = {t / tstar:.2f}, (L-L0)/L0 = {(Lf - L0) / L0:.3f}, H/H0 = {Hf / H0:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
