#!/usr/bin/env python3
"""What could lift a farm's balance above the floor of independent per-step swings, measured on a
cost trace (MPMXDEM_COST_TRACE, docs/design/farm.md "Grouping"): three remedies replayed on the
recorded RVE costs, beside a random grouping.

  tools/mpmxdem-tools balance_remedies docs/data/balance/biaxial_8x16_trace.csv.gz --ranks 16
  tools/mpmxdem-tools balance_remedies --self-test

For each number of ranks (one thread each), the balance (the ranks' mean over their maximum step
time, summed over the steps, as the log prints it) of:
- `random`: RVEs dealt at random, equal counts (mean, min and max over draws): what `spread`
  gives where neighbours are decorrelated;
- `covariance`: RVEs grouped so that each rank's summed cost varies least (a greedy fill that
  adds each RVE, most variable first, where its covariance with the rank's members is lowest),
  fitted on the first half of the steps and read on the second (out of sample) and on the first
  (in sample): whether the swings have a structure a static grouping can use;
- `moves K, m`: before every step up to K RVEs move from the most to the least loaded rank
  (the one whose cost is nearest half their gap), each move costing m seconds to both ranks, the
  costs known ahead (`oracle`: the step's own recorded costs, the best any predictor can do) or
  taken from the step before (`last`): a per-step migration.
The first --skip steps (start-up) are left out. numpy and pandas (exit 77 where missing).
"""
import argparse
import sys


def load(path, skip):
    import pandas as pd
    df = pd.read_csv(path)
    c = df.pivot(index="step", columns="rve", values="cpu_s").sort_index()
    return c.values[skip:]


def balance(owner, parts, costs):
    import numpy as np
    loads = np.stack([np.bincount(owner, row, parts) for row in costs])
    return float(loads.mean(axis=1).sum() / loads.max(axis=1).sum())


def random_owner(n, parts, rng):
    return rng.permutation(n) % parts


def covariance_owner(costs, parts):
    """Equal counts; each RVE, most variable first, to the open part where its covariance with
    the members is lowest (ties: the lowest part)."""
    import numpy as np
    n = costs.shape[1]
    cov = np.cov(costs.T)
    cap = -(-n // parts)
    owner = -np.ones(n, dtype=int)
    members = [[] for _ in range(parts)]
    for i in np.argsort(-np.diag(cov), kind="stable"):
        best = None
        for p in range(parts):
            if len(members[p]) >= cap:
                continue
            added = float(cov[i, members[p]].sum()) if members[p] else 0.0
            if best is None or added < best[0]:
                best = (added, p)
        owner[i] = best[1]
        members[best[1]].append(i)
    return owner


def with_moves(costs, parts, owner, k_moves, move_s, known):
    """Balance with up to k_moves per step planned on `known` ("oracle" or "last") costs; the
    moved RVEs stay where they went. Returns (balance, moves per step)."""
    import numpy as np
    own = owner.copy()
    loads = []
    moves = 0
    for s, row in enumerate(costs):
        guess = row if known == "oracle" else costs[s - 1] if s > 0 else row
        planned = np.bincount(own, guess, parts).astype(float)
        extra = np.zeros(parts)
        for _ in range(k_moves):
            total = planned + extra
            hi, lo = int(np.argmax(total)), int(np.argmin(total))
            gap = total[hi] - total[lo]
            mine = np.flatnonzero(own == hi)
            if mine.size == 0:
                break
            pick = int(mine[np.argmin(np.abs(guess[mine] - gap / 2))])
            if guess[pick] + 2.0 * move_s >= gap:
                break  # the move would not lower the maximum
            planned[hi] -= guess[pick]
            planned[lo] += guess[pick]
            extra[hi] += move_s
            extra[lo] += move_s
            own[pick] = lo
            moves += 1
        loads.append(np.bincount(own, row, parts) + extra)
    loads = np.array(loads)
    return float(loads.mean(axis=1).sum() / loads.max(axis=1).sum()), moves / len(costs)


def report(costs, ranks, draws, moves, move_costs, seed=1):
    import numpy as np
    rng = np.random.default_rng(seed)
    steps, n = costs.shape
    half = steps // 2
    cv = float(np.median(costs.std(axis=0) / costs.mean(axis=0)))
    print("%d steps, %d RVEs: median RVE step cost %.3g ms, median coefficient of variation %.2f"
          % (steps, n, 1e3 * float(np.median(costs)), cv))
    out = {}
    for parts in ranks:
        r = [balance(random_owner(n, parts, rng), parts, costs) for _ in range(draws)]
        cov_owner = covariance_owner(costs[:half], parts)
        row = {"random": (float(np.mean(r)), min(r), max(r)),
               "covariance_in": balance(cov_owner, parts, costs[:half]),
               "covariance_out": balance(cov_owner, parts, costs[half:])}
        print("%d ranks (%d RVEs each): random %.3f (%.3f-%.3f over %d draws); covariance %.3f out of "
              "sample (%.3f in sample)" % (parts, -(-n // parts), row["random"][0], row["random"][1],
                                           row["random"][2], draws, row["covariance_out"],
                                           row["covariance_in"]))
        start = random_owner(n, parts, rng)
        for known in ("oracle", "last"):
            for m in move_costs:
                cells = []
                for k in moves:
                    b, per = with_moves(costs, parts, start, k, m, known)
                    row[(known, m, k)] = (b, per)
                    cells.append("K=%d %.3f (%.1f moves/step)" % (k, b, per))
                print("  moves, %s costs, m = %.2g ms: %s" % (known, 1e3 * m, "; ".join(cells)))
        out[parts] = row
    return out


def self_test():
    """Independent swings: random grouping near the floor 1 / (1 + ~1.77 CV / sqrt(n)) at 16 parts,
    no structure for the covariance grouping to use out of sample, free oracle moves well above it,
    and moves that cost more than the swings they remove lower the balance."""
    import numpy as np
    rng = np.random.default_rng(3)
    steps, n, cv = 400, 512, 0.55
    costs = np.abs(1e-4 * (1.0 + cv * rng.standard_normal((steps, n))))
    out = report(costs, [16], draws=5, moves=[1, 8], move_costs=[0.0, 1e-3])[16]
    floor = 1.0 / (1.0 + 1.77 * cv / np.sqrt(32))
    assert abs(out["random"][0] - floor) < 0.03, (out["random"], floor)
    assert abs(out["covariance_out"] - out["random"][0]) < 0.03, out
    assert out["covariance_in"] > out["covariance_out"], out  # fitted noise: in sample only
    assert out[("oracle", 0.0, 8)][0] > out["random"][0] + 0.07, out  # 0.96 against 0.86
    assert out[("oracle", 1e-3, 8)][0] <= out[("oracle", 0.0, 8)][0], out
    assert out[("last", 0.0, 8)][0] < out["random"][0] + 0.03, out  # the past says nothing here
    print("balance_remedies self-test passed")


def main():
    ap = argparse.ArgumentParser(prog="mpmxdem-tools balance_remedies", description=__doc__.split("\n")[0])
    ap.add_argument("trace", nargs="?", help="a cost trace (CSV, or .csv.gz)")
    ap.add_argument("--ranks", type=int, nargs="+", default=[8, 16])
    ap.add_argument("--draws", type=int, default=20, help="random groupings per rank count")
    ap.add_argument("--moves", type=int, nargs="+", default=[1, 2, 4, 8], help="K: moves per step")
    ap.add_argument("--move-ms", type=float, nargs="+", default=[0.0, 0.1, 0.3, 1.0],
                    help="m: what one move costs each of its two ranks [ms]")
    ap.add_argument("--skip", type=int, default=5, help="start-up steps left out")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    try:
        import numpy  # noqa: F401
        import pandas  # noqa: F401
    except ImportError as e:
        print("balance_remedies: %s (numpy and pandas needed)" % e)
        return 77
    if args.self_test:
        self_test()
        return 0
    if not args.trace:
        ap.error("a trace is needed (or --self-test)")
    report(load(args.trace, args.skip), args.ranks, args.draws, args.moves, [1e-3 * m for m in args.move_ms])
    return 0


if __name__ == "__main__":
    sys.exit(main())
