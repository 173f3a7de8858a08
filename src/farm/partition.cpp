// METIS k-way partition of the RVE graph and reference splits (see header).
#include "farm/partition.hpp"

#include <metis.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include "common/errors.hpp"

namespace farm {

RveGraph cell_graph(const mpm::Grid& grid, const std::vector<common::Vec3>& x) {
  const std::size_t n = x.size();
  // Cell of every RVE (clamped into the grid), then cliques of the RVEs of each cell.
  std::map<std::int64_t, std::vector<std::int64_t>> by_cell;
  for (std::size_t k = 0; k < n; ++k) {
    std::int64_t c = 0;
    std::int64_t stride = 1;
    for (int a = 0; a < 3; ++a) {
      const double f = (x[k][a] - grid.origin[a]) / grid.spacing[a];
      auto i = static_cast<std::int64_t>(std::floor(std::isfinite(f) ? f : 0.0));
      i = std::clamp<std::int64_t>(i, 0, grid.cells[a] - 1);
      c += i * stride;
      stride *= grid.cells[a];
    }
    by_cell[c].push_back(static_cast<std::int64_t>(k));
  }
  std::vector<std::vector<std::int64_t>> adj(n);
  for (const auto& [cell, members] : by_cell) {
    for (std::int64_t a : members) {
      for (std::int64_t b : members) {
        if (a != b) adj[static_cast<std::size_t>(a)].push_back(b);
      }
    }
  }
  RveGraph g;
  g.xadj.assign(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    auto& row = adj[k];
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    g.xadj[k + 1] = g.xadj[k] + static_cast<std::int64_t>(row.size());
    g.adjncy.insert(g.adjncy.end(), row.begin(), row.end());
  }
  return g;
}

std::vector<int> partition_metis(const RveGraph& graph, const std::vector<double>& cost, int nparts,
                                 int seed) {
  const std::size_t n = graph.size();
  MPMXDEM_CHECK(cost.size() == n, "one cost per RVE");
  MPMXDEM_CHECK(nparts >= 1, "nparts >= 1");
  if (n == 0) return {};
  if (nparts == 1) return std::vector<int>(n, 0);
  if (static_cast<std::size_t>(nparts) >= n) {
    std::vector<int> owner(n);
    std::iota(owner.begin(), owner.end(), 0);
    return owner;
  }
  double cmax = 0.0;
  for (double c : cost) {
    MPMXDEM_CHECK(std::isfinite(c) && c >= 0.0, "RVE costs must be finite and >= 0");
    cmax = std::max(cmax, c);
  }
  // Integer weights: the total must fit idx_t (32-bit); 1e6 resolution per RVE at most.
  const double scale = cmax > 0.0 ? std::min(1e6, 1e9 / static_cast<double>(n)) / cmax : 0.0;
  std::vector<idx_t> vwgt(n);
  for (std::size_t k = 0; k < n; ++k) {
    vwgt[k] = std::max<idx_t>(1, static_cast<idx_t>(std::llround(cost[k] * scale)));
  }
  std::vector<idx_t> xadj(graph.xadj.begin(), graph.xadj.end());
  std::vector<idx_t> adjncy(graph.adjncy.begin(), graph.adjncy.end());
  if (adjncy.empty()) adjncy.push_back(0);  // METIS wants a valid pointer
  idx_t nv = static_cast<idx_t>(n);
  idx_t ncon = 1;
  idx_t np = nparts;
  idx_t objval = 0;
  std::vector<idx_t> part(n, 0);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = seed;
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_UFACTOR] = 10;  // allowed imbalance 1.010
  options[METIS_OPTION_NITER] = 20;
  options[METIS_OPTION_NCUTS] = 4;
  const int rc = METIS_PartGraphKway(&nv, &ncon, xadj.data(), adjncy.data(), vwgt.data(), nullptr,
                                     nullptr, &np, nullptr, nullptr, options, &objval, part.data());
  if (rc != METIS_OK) {
    throw common::InternalError("METIS_PartGraphKway failed with code " + std::to_string(rc) +
                                " (" + std::to_string(n) + " RVEs, " + std::to_string(nparts) +
                                " parts)");
  }
  std::vector<int> owner(part.begin(), part.end());
  refine_balance(owner, cost, nparts);
  return owner;
}

const char* to_string(PartitionStyle s) {
  return common::name_of(kPartitionStyleNames, s).data();  // the names are literals
}

PartitionStyle parse_partition_style(const std::string& s) {
  if (const auto p = common::value_of(kPartitionStyleNames, s)) return *p;
  throw common::InputError("partition style '" + s + "': must be one of " +
                           common::names_list(kPartitionStyleNames));
}

std::vector<int> partition_spread(const RveGraph& graph, const std::vector<double>& cost,
                                  int nparts, int seed) {
  const std::size_t n = graph.size();
  MPMXDEM_CHECK(cost.size() == n, "one cost per RVE");
  MPMXDEM_CHECK(nparts >= 1, "nparts >= 1");
  if (n == 0) return {};
  if (nparts == 1) return std::vector<int>(n, 0);
  const auto np = static_cast<std::size_t>(nparts);
  if (np >= n) {
    std::vector<int> owner(n);
    std::iota(owner.begin(), owner.end(), 0);
    return owner;
  }
  for (double c : cost)
    MPMXDEM_CHECK(std::isfinite(c) && c >= 0.0, "RVE costs must be finite and >= 0");
  const std::size_t ntiles = (n + np - 1) / np;
  const std::vector<int> tile = ntiles > 1 ? partition_metis(graph, std::vector<double>(n, 1.0),
                                                             static_cast<int>(ntiles), seed)
                                           : std::vector<int>(n, 0);
  std::vector<std::vector<std::size_t>> members(ntiles);
  for (std::size_t k = 0; k < n; ++k) members[static_cast<std::size_t>(tile[k])].push_back(k);
  std::vector<int> owner(n, 0);
  std::vector<double> load(np, 0.0);
  std::vector<char> used(np, 0);
  // Equal costs would otherwise send every tile's first member to part 0, its second to part 1,
  // ...: the same position in every tile (an edge of the specimen, a row) on the same part,
  // correlated again. A seeded shuffle of each tile first (Fisher-Yates on mt19937_64's
  // standard-defined output: the same on every platform).
  std::mt19937_64 rng(static_cast<std::uint64_t>(seed));
  for (std::vector<std::size_t>& m : members) {
    for (std::size_t i = m.size(); i > 1; --i) std::swap(m[i - 1], m[rng() % i]);
    std::stable_sort(m.begin(), m.end(),
                     [&](std::size_t a, std::size_t b) { return cost[a] > cost[b]; });
    std::fill(used.begin(), used.end(), 0);
    std::size_t taken = 0;
    for (const std::size_t k : m) {
      if (taken == np) {
        std::fill(used.begin(), used.end(), 0);
        taken = 0;
      }
      std::size_t best = np;
      for (std::size_t p = 0; p < np; ++p) {
        if (used[p] == 0 && (best == np || load[p] < load[best])) best = p;
      }
      used[best] = 1;
      ++taken;
      owner[k] = static_cast<int>(best);
      load[best] += cost[k];
    }
  }
  refine_balance(owner, cost, nparts);
  return owner;
}

std::vector<int> partition_fresh(PartitionStyle style, const RveGraph& graph,
                                 const std::vector<double>& cost, int nparts, int seed) {
  return style == PartitionStyle::cells ? partition_metis(graph, cost, nparts, seed)
                                        : partition_spread(graph, cost, nparts, seed);
}

std::vector<int> partition_round_robin(std::size_t n, int nparts) {
  std::vector<int> owner(n);
  for (std::size_t k = 0; k < n; ++k)
    owner[k] = static_cast<int>(k % static_cast<std::size_t>(nparts));
  return owner;
}

std::vector<int> partition_blocks(std::size_t n, int nparts) {
  std::vector<int> owner(n);
  const auto np = static_cast<std::size_t>(nparts);
  for (std::size_t k = 0; k < n; ++k)
    owner[k] = static_cast<int>(k * np / std::max<std::size_t>(n, 1));
  return owner;
}

std::vector<double> part_loads(const std::vector<int>& owner, const std::vector<double>& cost,
                               int nparts) {
  std::vector<double> load(static_cast<std::size_t>(nparts), 0.0);
  for (std::size_t k = 0; k < owner.size(); ++k)
    load[static_cast<std::size_t>(owner[k])] += cost[k];
  return load;
}

double balance_efficiency(const std::vector<int>& owner, const std::vector<double>& cost,
                          int nparts) {
  const std::vector<double> load = part_loads(owner, cost, nparts);
  const double mx = *std::max_element(load.begin(), load.end());
  if (!(mx > 0.0)) return 1.0;
  const double mean = std::accumulate(load.begin(), load.end(), 0.0) / nparts;
  return mean / mx;
}

void refine_balance(std::vector<int>& owner, const std::vector<double>& cost, int nparts) {
  std::vector<double> load = part_loads(owner, cost, nparts);
  // Greedy moves from the heaviest part to the lightest while they lower the larger of the two;
  // deterministic (ties: lowest index). Bounded: every move strictly reduces the pair's maximum.
  for (std::size_t iter = 0; iter < 4 * owner.size(); ++iter) {
    const auto h = static_cast<int>(std::max_element(load.begin(), load.end()) - load.begin());
    const auto l = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    const double gap = load[static_cast<std::size_t>(h)] - load[static_cast<std::size_t>(l)];
    std::size_t best = owner.size();
    double best_dev = gap;  // |new gap| must beat the current one
    for (std::size_t k = 0; k < owner.size(); ++k) {
      if (owner[k] != h || !(cost[k] > 0.0)) continue;
      const double dev = std::abs(gap - 2.0 * cost[k]);
      if (dev < best_dev) {
        best_dev = dev;
        best = k;
      }
    }
    if (best == owner.size()) break;
    owner[best] = l;
    load[static_cast<std::size_t>(h)] -= cost[best];
    load[static_cast<std::size_t>(l)] += cost[best];
  }
}

namespace {

// The state of incremental_descent: the owners, the parts' loads (also ordered by load), each
// part's members, and the steps taken so far.
class Descent {
 public:
  Descent(const RveGraph& graph, const std::vector<int>& start, const std::vector<double>& cost,
          int nparts)
      : graph_(graph),
        start_(start),
        cost_(cost),
        owner_(start),
        np_(static_cast<std::size_t>(nparts)),
        load_(np_, 0.0),
        members_(np_),
        slot_(start.size()) {
    for (std::size_t k = 0; k < owner_.size(); ++k) {
      const auto o = static_cast<std::size_t>(owner_[k]);
      load_[o] += cost_[k];
      slot_[k] = members_[o].size();
      members_[o].push_back(k);
    }
    for (std::size_t p = 0; p < np_; ++p) by_load_.emplace(load_[p], static_cast<int>(p));
  }

  [[nodiscard]] double total_load() const {
    return std::accumulate(load_.begin(), load_.end(), 0.0);
  }

  // One move or swap off the heaviest part while its load is above stop_load; false: none left.
  bool improve(double stop_load) {
    top_ = by_load_.rbegin()->first;
    if (top_ <= stop_load) return false;
    h_ = by_load_.lower_bound({top_, std::numeric_limits<int>::min()})->second;
    lightest_ = by_load_.begin()->second;
    // The largest load of the other parts (h excluded): what the global max falls to at best.
    const auto last = std::prev(by_load_.end());
    second_ = last->second != h_         ? last->first
              : last == by_load_.begin() ? 0.0
                                         : std::prev(last)->first;
    return try_move() || try_swap();
  }

  std::vector<DescentStep> steps;

 private:
  // A move's rank (see header): global max after it, not-a-neighbour, pair max, RVE, part.
  using Key = std::tuple<double, int, double, std::size_t, int>;
  // A swap's rank: global max after it, pair max, RVE of the heaviest part, RVE of the lightest.
  using SwapKey = std::tuple<double, double, std::size_t, std::size_t>;

  // The best single move of an RVE of h to a neighbouring part or to the lightest one.
  bool try_move() {
    bool found = false;
    Key best{};
    for (const std::size_t k : members_[static_cast<std::size_t>(h_)]) {
      const double c = cost_[k];
      if (!(c > 0.0)) continue;
      near_.clear();
      for (std::int64_t e = graph_.xadj[k]; e < graph_.xadj[k + 1]; ++e) {
        const int o = owner_[static_cast<std::size_t>(graph_.adjncy[static_cast<std::size_t>(e)])];
        if (o != h_) near_.push_back(o);
      }
      std::sort(near_.begin(), near_.end());
      near_.erase(std::unique(near_.begin(), near_.end()), near_.end());
      const auto consider = [&](int d, bool neighbour) {
        const double to = load_[static_cast<std::size_t>(d)] + c;
        if (!(to < top_)) return;  // the pair's max must fall
        const double pair = std::max(top_ - c, to);
        const Key key{std::max(pair, second_), neighbour ? 0 : 1, pair, k, d};
        if (!found || key < best) {
          best = key;
          found = true;
        }
      };
      for (const int d : near_) consider(d, true);
      if (lightest_ != h_ && !std::binary_search(near_.begin(), near_.end(), lightest_))
        consider(lightest_, false);
    }
    if (!found) return false;
    const std::size_t k = std::get<3>(best);
    const int d = std::get<4>(best);
    shift(d, cost_[k]);
    relocate(k, d);
    return true;
  }

  // No RVE of h fits anywhere: swap one of h with a cheaper one of the lightest part, the pair
  // whose cost difference delta is nearest to half their gap (delta in (0, gap) lowers the
  // pair's max). For each RVE of h the two costs nearest to the ideal, found by bisection in
  // the lightest part's sorted costs, are the only candidates (the pair max is convex in delta).
  bool try_swap() {
    if (lightest_ == h_) return false;
    const auto hu = static_cast<std::size_t>(h_);
    const auto lu = static_cast<std::size_t>(lightest_);
    const double gap = top_ - load_[lu];
    by_cost_.clear();
    for (const std::size_t b : members_[lu]) by_cost_.emplace_back(cost_[b], b);
    std::sort(by_cost_.begin(), by_cost_.end());
    bool swap_found = false;
    SwapKey best_swap{};
    for (const std::size_t a : members_[hu]) {
      const auto at = std::lower_bound(by_cost_.begin(), by_cost_.end(),
                                       std::make_pair(cost_[a] - 0.5 * gap, std::size_t{0}));
      for (auto it = at == by_cost_.begin() ? at : std::prev(at); it != by_cost_.end() && it <= at;
           ++it) {
        const double delta = cost_[a] - it->first;
        if (!(delta > 0.0 && delta < gap)) continue;
        const double pair = std::max(top_ - delta, load_[lu] + delta);
        const SwapKey key{std::max(pair, second_), pair, a, it->second};
        if (!swap_found || key < best_swap) {
          best_swap = key;
          swap_found = true;
        }
      }
    }
    if (!swap_found) return false;
    const std::size_t a = std::get<2>(best_swap);
    const std::size_t b = std::get<3>(best_swap);
    shift(lightest_, cost_[a] - cost_[b]);
    relocate(a, lightest_);
    steps.back().ends_a_move = false;
    relocate(b, h_);
    return true;
  }

  void relocate(std::size_t k, int to) {
    // Swap-remove k from its part's members (their order does not matter: the keys decide).
    std::vector<std::size_t>& from = members_[static_cast<std::size_t>(owner_[k])];
    from[slot_[k]] = from.back();
    slot_[from.back()] = slot_[k];
    from.pop_back();
    slot_[k] = members_[static_cast<std::size_t>(to)].size();
    members_[static_cast<std::size_t>(to)].push_back(k);
    moved_ += (owner_[k] == start_[k] ? 1 : 0) - (to == start_[k] ? 1 : 0);
    owner_[k] = to;
    steps.push_back({k, to, true, by_load_.rbegin()->first, moved_});
  }

  void shift(int d, double delta) {  // delta of load from h to d
    const auto hu = static_cast<std::size_t>(h_);
    const auto du = static_cast<std::size_t>(d);
    by_load_.erase({load_[hu], h_});
    by_load_.erase({load_[du], d});
    load_[hu] -= delta;
    load_[du] += delta;
    by_load_.emplace(load_[hu], h_);
    by_load_.emplace(load_[du], d);
  }

  const RveGraph& graph_;
  const std::vector<int>& start_;
  const std::vector<double>& cost_;
  std::vector<int> owner_;
  std::size_t np_;
  std::vector<double> load_;
  std::vector<std::vector<std::size_t>> members_;
  std::vector<std::size_t> slot_;  // position of RVE k in members_[owner_[k]]
  // Parts ordered by (load, label): the lightest is the first, the heaviest the lowest label at
  // the last load.
  std::set<std::pair<double, int>> by_load_;
  std::int64_t moved_ = 0;
  // This round's heaviest load, its part, the lightest part, the largest load of the others.
  double top_ = 0.0;
  int h_ = 0;
  int lightest_ = 0;
  double second_ = 0.0;
  std::vector<int> near_;                                // scratch of try_move
  std::vector<std::pair<double, std::size_t>> by_cost_;  // scratch of try_swap
};

}  // namespace

std::vector<DescentStep> incremental_descent(const RveGraph& graph, const std::vector<int>& start,
                                             const std::vector<double>& cost, int nparts,
                                             double stop_imbalance) {
  const std::size_t n = start.size();
  MPMXDEM_CHECK(cost.size() == n && graph.size() == n,
                "one cost and one owner per RVE of the graph");
  MPMXDEM_CHECK(nparts >= 1, "nparts >= 1");
  for (std::size_t k = 0; k < n; ++k) {
    MPMXDEM_CHECK(start[k] >= 0 && start[k] < nparts, "owners must lie in [0, nparts)");
    MPMXDEM_CHECK(std::isfinite(cost[k]) && cost[k] >= 0.0, "RVE costs must be finite and >= 0");
  }
  if (nparts == 1 || n == 0) return {};
  Descent descent(graph, start, cost, nparts);
  const double stop_load = stop_imbalance * descent.total_load() / static_cast<double>(nparts);
  // Every move lowers the sum of squared loads; the cap only guards against the unforeseen.
  for (std::size_t move = 0; move < 4 * n + static_cast<std::size_t>(nparts); ++move) {
    if (!descent.improve(stop_load)) break;
  }
  return std::move(descent.steps);
}

std::vector<int> apply_descent(std::vector<int> owner, const std::vector<DescentStep>& steps,
                               std::size_t count) {
  MPMXDEM_CHECK(count <= steps.size(), "at most the steps of the descent");
  for (std::size_t s = 0; s < count; ++s) owner[steps[s].rve] = steps[s].to;
  return owner;
}

std::size_t descent_cut(const std::vector<DescentStep>& steps, double mean_load, double slack) {
  if (steps.empty()) return 0;
  const double target = steps.back().max_load + 0.5 * slack * mean_load;
  for (std::size_t s = 0; s < steps.size(); ++s) {
    if (steps[s].ends_a_move && steps[s].max_load <= target) return s + 1;
  }
  return steps.size();
}

std::vector<int> partition_incremental(const RveGraph& graph, std::vector<int> owner,
                                       const std::vector<double>& cost, int nparts, double slack) {
  MPMXDEM_CHECK(slack >= 0.0, "slack >= 0");
  const std::vector<DescentStep> steps =
      incremental_descent(graph, owner, cost, nparts, 1.0 + 0.5 * slack);
  const double mean = std::accumulate(cost.begin(), cost.end(), 0.0) / nparts;
  return apply_descent(std::move(owner), steps, descent_cut(steps, mean, slack));
}

std::int64_t keep_owners(const std::vector<int>& current, std::vector<int>& proposal, int nparts) {
  MPMXDEM_CHECK(current.size() == proposal.size(), "one current and one proposed owner per RVE");
  const auto np = static_cast<std::int64_t>(nparts);
  // Greedy matching of new parts onto old ones by the RVEs they share, largest share first (ties:
  // smallest new part, then smallest old one). Only the (new, old) pairs that share RVEs can
  // score: they are counted by sorting the N pair keys, O(N log N) time and O(N) memory (the
  // dense P x P table and its O(P^3) scan took 145 s at 4096 parts: docs/validation/scaling.md).
  std::vector<std::int64_t> keys(current.size());
  for (std::size_t k = 0; k < current.size(); ++k) keys[k] = proposal[k] * np + current[k];
  std::sort(keys.begin(), keys.end());
  struct Pair {
    std::int64_t shared;
    std::int64_t key;  // new * np + old
  };
  std::vector<Pair> pairs;
  for (std::size_t k = 0; k < keys.size();) {
    std::size_t e = k;
    while (e < keys.size() && keys[e] == keys[k]) ++e;
    pairs.push_back({static_cast<std::int64_t>(e - k), keys[k]});
    k = e;
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) {
    return x.shared != y.shared ? x.shared > y.shared : x.key < y.key;
  });
  const auto nu = static_cast<std::size_t>(nparts);
  std::vector<int> rename(nu, -1);
  std::vector<bool> taken(nu, false);
  for (const Pair& pr : pairs) {
    const auto n = static_cast<std::size_t>(pr.key / np);
    const auto o = static_cast<std::size_t>(pr.key % np);
    if (rename[n] >= 0 || taken[o]) continue;
    rename[n] = static_cast<int>(o);
    taken[o] = true;
  }
  // New parts that share nothing with a free old part: smallest with smallest, as the scan did.
  std::size_t o = 0;
  for (std::size_t n = 0; n < nu; ++n) {
    if (rename[n] >= 0) continue;
    while (taken[o]) ++o;
    rename[n] = static_cast<int>(o);
    taken[o] = true;
  }
  std::int64_t moves = 0;
  for (std::size_t k = 0; k < proposal.size(); ++k) {
    proposal[k] = rename[static_cast<std::size_t>(proposal[k])];
    moves += proposal[k] != current[k] ? 1 : 0;
  }
  return moves;
}

}  // namespace farm
