#!/usr/bin/env python3
"""The balance table of docs/design/farm.md ("Grouping"): the farm's balancing replayed
(balance_replay, src/farm/tools/balance_replay.cpp) on the stored cost trace of the 8 x 16
biaxial (docs/data/balance/), for the layouts of the 16-core node, beside what the node measured
(docs/data/node16/summary.txt, made with the cells grouping).

  tools/mpmxdem-tools balance_table --replay build/src/farm/balance_replay           # prints the table
  tools/mpmxdem-tools balance_table --replay BIN --check docs/design/farm.md         # exit 1 if it differs

The table sits between the lines `<!-- balance_table:begin ... -->` and
`<!-- balance_table:end -->` of the document (test farm.balance_replay.doc_table).
Stdlib only.
"""
import argparse
import gzip
import os
import re
import shutil
import subprocess
import sys
import tempfile

from ..paths import ROOT
DATA = os.path.join(ROOT, "docs", "data", "balance")
TRACE = "biaxial_8x16_trace.csv"
NODE = os.path.join(ROOT, "docs", "data", "node16", "summary.txt")
LAYOUTS = [(2, 1), (4, 1), (8, 1), (16, 1), (8, 2), (4, 4), (2, 8), (1, 16)]
BEGIN = "<!-- balance_table:begin"
END = "<!-- balance_table:end -->"


def node_balances():
    """{(ranks, threads): balance} of section D of the node's summary."""
    out = {}
    pat = re.compile(r"ranks x threads (\d+)x(\d+): .* balance ([0-9.]+)")
    with open(NODE, encoding="utf-8") as f:
        for line in f:
            m = pat.search(line)
            if m:
                out[(int(m.group(1)), int(m.group(2)))] = float(m.group(3))
    return out


def replay(binary, trace, partition, ranks, threads):
    """{ranks: (balance, core efficiency)} printed by balance_replay."""
    run = subprocess.run([binary, trace, "--ranks", ",".join(str(r) for r in ranks),
                          "--threads", str(threads), "--partition", partition],
                         capture_output=True, text=True, check=True)
    out = {}
    for line in run.stdout.splitlines():
        f = line.split()
        if len(f) >= 4 and f[0].isdigit() and f[1].isdigit():
            out[int(f[0])] = (float(f[2]), float(f[3]))
    return out


def table(binary):
    tmp = tempfile.mkdtemp(prefix="balance_table_")
    try:
        trace = os.path.join(tmp, TRACE)
        with gzip.open(os.path.join(DATA, TRACE + ".gz"), "rb") as src, open(trace, "wb") as dst:
            shutil.copyfileobj(src, dst)
        for ext in (".graph.csv", ".start.csv"):
            shutil.copy(os.path.join(DATA, TRACE + ext), trace + ext)
        res = {}
        for part in ("cells", "spread"):
            for threads in sorted({t for _, t in LAYOUTS}):
                ranks = [r for r, t in LAYOUTS if t == threads]
                for r, v in replay(binary, trace, part, ranks, threads).items():
                    res[(part, r, threads)] = v
    finally:
        shutil.rmtree(tmp)
    node = node_balances()
    rows = ["| ranks x threads | RVEs per rank | node, cells (measured) | replay, cells | "
            "replay, spread | replay, spread: share of the cores' time in RVEs |",
            "|---|---|---|---|---|---|"]
    for r, t in LAYOUTS:
        measured = f"{node[(r, t)]:.3f}" if (r, t) in node else "not run"
        rows.append(f"| {r} x {t} | {512 // r} | {measured} | {res[('cells', r, t)][0]:.3f} | "
                    f"{res[('spread', r, t)][0]:.3f} | {res[('spread', r, t)][1]:.3f} |")
    return "\n".join(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--replay", required=True, help="the balance_replay program")
    ap.add_argument("--check", help="a document whose marked table must equal the printed one")
    a = ap.parse_args()
    text = table(a.replay)
    if not a.check:
        print(text)
        return 0
    lines = open(a.check, encoding="utf-8").read().split("\n")
    try:
        b = next(i for i, l in enumerate(lines) if l.startswith(BEGIN))
        e = next(i for i, l in enumerate(lines) if i > b and l.startswith(END))
    except StopIteration:
        print(f"{a.check}: no '{BEGIN} ... {END}' block")
        return 1
    have = "\n".join(lines[b + 1:e]).strip("\n")
    if have != text:
        print(f"{a.check}:{b + 2}: the balance table differs from what the replay prints today:")
        print("in the document:\n" + have + "\nfrom the replay:\n" + text)
        return 1
    print(f"{a.check}: the balance table is current")
    return 0


if __name__ == "__main__":
    sys.exit(main())
