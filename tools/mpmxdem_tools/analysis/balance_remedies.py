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
  costs known ahead (`oracle`: the step's own recorded costs, the best any predictor can do),
  taken from the step before (`last`), or, where the trace has the columns dem_steps and
  rebuilds: `predicted`, the step's DEM step count (which an RVE fixes from its increment and
  pressure before it runs, eq. 11 of docs/design/rve_step.md) times its cost per DEM step at its
  last step with DEM steps (an RVE step without DEM steps: its last such step's cost); `work`,
  the step's work as the least-squares fit a + b dem_steps + c rebuilds of the costs prices it
  (what a planner that knew each RVE's DEM steps and neighbour-list builds ahead would see).
With --repeat, a trace of the same run recorded again (the same DEM work, bit for bit; another
draw of the machine's timing): how much of the swings is work and how much timing noise,
i.e. random groupings on the measured costs, on the work model, on the DEM steps alone, and the
work equalised exactly with the repeat's noise left (the ceiling of any placement that knows the
work).
The first --skip steps (start-up) are left out. numpy and pandas (exit 77 where missing).
"""
import argparse
import sys


def load(path, skip):
    """(costs, DEM step counts, neighbour-list builds) as [step, rve] arrays; the counts None
    where the trace has none (traces of before the columns)."""
    import pandas as pd
    df = pd.read_csv(path)

    def table(col):
        return df.pivot(index="step", columns="rve", values=col).sort_index().values[skip:]
    if "dem_steps" not in df.columns:
        return table("cpu_s"), None, None
    return table("cpu_s"), table("dem_steps").astype(float), table("rebuilds").astype(float)


def work_model(costs, dem_steps, rebuilds):
    """The least-squares fit costs ~ a + b dem_steps + c rebuilds: (its values, (a, b, c))."""
    import numpy as np
    x = np.stack([np.ones_like(dem_steps), dem_steps, rebuilds], axis=-1)
    coef, *_ = np.linalg.lstsq(x.reshape(-1, 3), costs.ravel(), rcond=None)
    return x @ coef, coef


def guesses(costs, dem_steps, known, rebuilds=None):
    """What a planner knows of each step's costs before it runs: the costs themselves (`oracle`),
    the step before's (`last`), the step's DEM step counts times each RVE's last cost per DEM
    step (`predicted`), or the fitted price of the step's work (`work`; see the module's text)."""
    import numpy as np
    if known == "oracle":
        return costs
    if known == "work":
        return work_model(costs, dem_steps, rebuilds)[0]
    guess = np.empty_like(costs)
    guess[0] = costs[0]
    guess[1:] = costs[:-1]
    if known == "last":
        return guess
    per_step = np.full(costs.shape[1], np.nan)  # cost per DEM step, at the last step with some
    idle = np.full(costs.shape[1], np.nan)  # cost of the last step without
    for s in range(costs.shape[0]):
        n = dem_steps[s]
        if s > 0:
            pred = np.where(n > 0, n * per_step, idle)
            guess[s] = np.where(np.isfinite(pred), pred, costs[s - 1])
        stepped = dem_steps[s] > 0
        per_step[stepped] = costs[s][stepped] / dem_steps[s][stepped]
        idle[~stepped] = costs[s][~stepped]
    return guess


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
    """Balance with up to k_moves per step planned on `known` (guesses()) costs; the moved RVEs
    stay where they went. Returns (balance, moves per step)."""
    import numpy as np
    own = owner.copy()
    loads = []
    moves = 0
    for s, row in enumerate(costs):
        guess = known[s]
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


def report(costs, ranks, draws, moves, move_costs, seed=1, dem_steps=None, rebuilds=None):
    import numpy as np
    rng = np.random.default_rng(seed)
    steps, n = costs.shape
    half = steps // 2
    cv = float(np.median(costs.std(axis=0) / costs.mean(axis=0)))
    print("%d steps, %d RVEs: median RVE step cost %.3g ms, median coefficient of variation %.2f"
          % (steps, n, 1e3 * float(np.median(costs)), cv))
    knowns = ["oracle", "last"] + (["predicted"] if dem_steps is not None else []) + \
        (["work"] if rebuilds is not None else [])
    known = {k: guesses(costs, dem_steps, k, rebuilds) for k in knowns}
    if rebuilds is not None:
        coef = work_model(costs, dem_steps, rebuilds)[1]
        print("  work: %.4f ms + %.4f ms per DEM step + %.3f ms per neighbour-list build (%.2f %% of "
              "RVE steps build)" % (1e3 * coef[0], 1e3 * coef[1], 1e3 * coef[2],
                                    100 * float((rebuilds > 0).mean())))
    for k in knowns[1:]:
        err = np.abs(known[k][1:] - costs[1:]) / costs[1:]
        print("  %s costs: an RVE step's cost within %.0f %% (median), %.0f %% (90th percentile)"
              % (k, 100 * float(np.median(err)), 100 * float(np.percentile(err, 90))))
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
        for kn in knowns:
            for m in move_costs:
                cells = []
                for k in moves:
                    b, per = with_moves(costs, parts, start, k, m, known[kn])
                    row[(kn, m, k)] = (b, per)
                    cells.append("K=%d %.3f (%.1f moves/step)" % (k, b, per))
                print("  moves, %s costs, m = %.2g ms: %s" % (kn, 1e3 * m, "; ".join(cells)))
        out[parts] = row
    return out


def decompose(costs, repeat, dem_steps, rebuilds, ranks, draws, seed=1):
    """Work against timing noise, from two traces of the same run (the module's text). Returns
    {parts: {name: balance}}."""
    import numpy as np
    rng = np.random.default_rng(seed)
    n = costs.shape[1]
    model, coef = work_model(costs, dem_steps, rebuilds)
    steps_only = coef[0] + coef[1] * dem_steps
    corr = [np.corrcoef(costs[:, k], repeat[:, k])[0, 1] for k in range(n)]
    print("repeat: an RVE's step costs correlate %.2f (median over RVEs) with the same run's again; "
          "all RVE steps pooled %.2f; the work model fitted on the first with the repeat %.2f"
          % (float(np.median(corr)), float(np.corrcoef(costs.ravel(), repeat.ravel())[0, 1]),
             float(np.corrcoef(model.ravel(), repeat.ravel())[0, 1])))
    out = {}
    for parts in ranks:
        def rand(c):
            return float(np.mean([balance(random_owner(n, parts, rng), parts, c) for _ in range(draws)]))
        ceiling = []
        for _ in range(draws):
            own = random_owner(n, parts, rng)
            noise = np.stack([np.bincount(own, row, parts) for row in repeat - model])
            loads = model.sum(axis=1)[:, None] / parts + noise
            ceiling.append(float(loads.mean(axis=1).sum() / loads.max(axis=1).sum()))
        row = {"measured": rand(costs), "repeat": rand(repeat), "work": rand(model),
               "dem_steps": rand(steps_only), "ceiling": float(np.mean(ceiling))}
        print("%d ranks, random groupings: measured %.3f (repeat %.3f), work model %.3f, DEM steps "
              "alone %.3f; the work equalised exactly, the repeat's noise left: %.3f"
              % (parts, row["measured"], row["repeat"], row["work"], row["dem_steps"], row["ceiling"]))
        out[parts] = row
    return out


def self_test():
    """Independent swings: random grouping near the floor 1 / (1 + ~1.77 CV / sqrt(n)) at 16 parts,
    no structure for the covariance grouping to use out of sample, free oracle moves well above it,
    and moves that cost more than the swings they remove lower the balance."""
    import numpy as np
    rng = np.random.default_rng(3)
    steps, n, cv = 400, 512, 0.55
    # Each RVE's cost is its DEM step count (1-12, drawn afresh every step: independent swings)
    # times a cost per DEM step that drifts slowly: what the step count predicts.
    dem = rng.integers(1, 13, size=(steps, n))
    per_step = 1e-5 * (1.0 + 0.3 * rng.random(n)) * (1.0 + 1e-3 * np.arange(steps))[:, None]
    costs = dem * per_step
    cv = float(np.median(costs.std(axis=0) / costs.mean(axis=0)))
    out = report(costs, [16], draws=5, moves=[1, 8], move_costs=[0.0, 1e-3], dem_steps=dem)[16]
    floor = 1.0 / (1.0 + 1.77 * cv / np.sqrt(32))
    assert abs(out["random"][0] - floor) < 0.03, (out["random"], floor)
    assert abs(out["covariance_out"] - out["random"][0]) < 0.03, out
    assert out["covariance_in"] > out["covariance_out"], out  # fitted noise: in sample only
    assert out[("oracle", 0.0, 8)][0] > out["random"][0] + 0.07, out  # 0.96 against 0.86
    assert out[("oracle", 1e-3, 8)][0] <= out[("oracle", 0.0, 8)][0], out
    assert out[("last", 0.0, 8)][0] < out["random"][0] + 0.03, out  # the past says nothing here
    # The step counts say it all but the drift: the predicted moves are the oracle's within 0.01.
    assert abs(out[("predicted", 0.0, 8)][0] - out[("oracle", 0.0, 8)][0]) < 0.01, out
    g = guesses(costs, dem, "predicted")
    assert np.allclose(g[1:], costs[1:], rtol=2e-3), "the prediction misses the drift by 1e-3 only"
    # Work = 1e-5 + 2e-5 per DEM step + 5e-4 per build, and timing noise that a repeat redraws:
    # the fit finds the prices, the noise-free groupings beat the measured ones, and the ceiling
    # (work equalised, noise left) lies between the measured and 1.
    builds = (rng.random((steps, n)) < 0.01).astype(float)
    work = 1e-5 + 2e-5 * dem + 5e-4 * builds
    noisy = [work * np.exp(0.2 * rng.standard_normal(work.shape)) for _ in range(2)]
    coef = work_model(noisy[0], dem.astype(float), builds)[1]
    assert np.allclose(coef, [1e-5, 2e-5, 5e-4], rtol=0.1, atol=2e-6), coef
    d = decompose(noisy[0], noisy[1], dem.astype(float), builds, [16], draws=3)[16]
    assert d["measured"] < d["work"] < d["dem_steps"], d
    assert d["measured"] < d["ceiling"] < 1.0, d
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
    ap.add_argument("--repeat", help="a trace of the same run recorded again (work against noise)")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    try:
        import numpy as np
        import pandas  # noqa: F401
    except ImportError as e:
        print("balance_remedies: %s (numpy and pandas needed)" % e)
        return 77
    if args.self_test:
        self_test()
        return 0
    if not args.trace:
        ap.error("a trace is needed (or --self-test)")
    costs, dem_steps, rebuilds = load(args.trace, args.skip)
    if args.repeat:
        repeat, n2, b2 = load(args.repeat, args.skip)
        if dem_steps is None or n2 is None or repeat.shape != costs.shape or \
                not (np.array_equal(n2, dem_steps) and np.array_equal(b2, rebuilds)):
            print("balance_remedies: --repeat needs two traces of the same run, with the columns "
                  "dem_steps and rebuilds, whose DEM work is the same", file=sys.stderr)
            return 2
        decompose(costs, repeat, dem_steps, rebuilds, args.ranks, args.draws)
    report(costs, args.ranks, args.draws, args.moves, [1e-3 * m for m in args.move_ms],
           dem_steps=dem_steps, rebuilds=rebuilds)
    return 0


if __name__ == "__main__":
    sys.exit(main())
