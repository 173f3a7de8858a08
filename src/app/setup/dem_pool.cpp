// The DEM RVEs of a coupled job on one rank: see dem_pool.hpp.
#include "app/setup/dem_pool.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <exception>
#include <functional>
#include <optional>
#include <set>
#include <sstream>

#include "app/setup/dem_setup.hpp"
#include "common/errors.hpp"
#include "common/state_store.hpp"
#include "dem/element_test.hpp"
#include "dem/measures.hpp"
#include "dem/state.hpp"
#include "dem/stress_target.hpp"
#include "farm/exchange.hpp"
#include "farm/mpi_util.hpp"

namespace app {

namespace {

using Key = DemPool::Key;

struct Failure {
  farm::ErrorKind kind = farm::ErrorKind::none;
  std::string message;
};

/// Runs make(j, lines) for j < n on the rank's threads (dynamic, one at a time: preparations
/// differ in cost); each job's log lines go to lines[j]. Returns the first failure in the order
/// of j (none if none).
Failure in_parallel(std::size_t n,
                    const std::function<void(std::size_t, std::vector<std::string>&)>& make,
                    std::vector<std::vector<std::string>>& lines) {
  lines.assign(n, {});
  std::vector<Failure> failed(n);
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(dynamic, 1) if (n > 1)
  for (std::int64_t j = 0; j < count; ++j) {
    const auto u = static_cast<std::size_t>(j);
    try {
      make(u, lines[u]);
    } catch (const std::exception& e) {
      failed[u] = Failure{farm::current_error_kind(), e.what()};
    } catch (...) {
      failed[u] = Failure{farm::ErrorKind::internal, "unknown exception"};
    }
  }
  for (Failure& f : failed)
    if (f.kind != farm::ErrorKind::none) return std::move(f);
  return {};
}

/// Collective: every rank's keys, by rank.
std::vector<std::set<Key>> allgather_keys(MPI_Comm comm, const std::set<Key>& mine) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<std::int64_t> flat;
  for (const Key& k : mine) {
    flat.push_back(k.first);
    flat.push_back(k.second);
  }
  const int n = farm::to_count(flat.size());
  std::vector<int> counts(static_cast<std::size_t>(size));
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::vector<int> displs(static_cast<std::size_t>(size), 0);
  for (std::size_t r = 1; r < displs.size(); ++r) displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<std::int64_t> all(static_cast<std::size_t>(displs.back() + counts.back()));
  MPI_Allgatherv(flat.data(), n, MPI_INT64_T, all.data(), counts.data(), displs.data(), MPI_INT64_T,
                 comm);
  std::vector<std::set<Key>> out(static_cast<std::size_t>(size));
  for (std::size_t r = 0; r < out.size(); ++r) {
    for (int j = 0; j < counts[r]; j += 2) {
      const auto at = static_cast<std::size_t>(displs[r] + j);
      out[r].insert(Key{static_cast<std::int32_t>(all[at]), all[at + 1]});
    }
  }
  return out;
}

/// Where each of `keys` comes from: the lowest rank that holds it (holds[r]: rank r's keys),
/// else a rank that makes it, round robin over the keys nobody holds. made[i]: made, not held.
struct Sources {
  std::vector<int> rank;
  std::vector<bool> made;
};
Sources sources(const std::vector<Key>& keys, const std::vector<std::set<Key>>& holds) {
  Sources s;
  std::size_t unheld = 0;
  for (const Key& k : keys) {
    int holder = -1;
    for (std::size_t r = 0; r < holds.size() && holder < 0; ++r)
      if (holds[r].count(k) != 0) holder = static_cast<int>(r);
    s.made.push_back(holder < 0);
    s.rank.push_back(holder >= 0 ? holder : static_cast<int>(unheld++ % holds.size()));
  }
  return s;
}

/// Collective: rank 0 logs the lines of every item made (src.made), in the order of the items;
/// `lines` holds this rank's, in that order.
void log_in_order(MPI_Comm comm, const Sources& src,
                  const std::vector<std::vector<std::string>>& lines) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::vector<std::string> joined;
  for (const auto& item : lines) {
    std::string s;
    for (const std::string& l : item) s += l + "\n";
    joined.push_back(std::move(s));
  }
  const std::vector<std::string> all = farm::allgather_strings(comm, joined);
  if (rank != 0) return;
  std::vector<std::size_t> start(static_cast<std::size_t>(size) + 1, 0);  // rank r's in `all`
  for (std::size_t i = 0; i < src.rank.size(); ++i)
    if (src.made[i]) ++start[static_cast<std::size_t>(src.rank[i]) + 1];
  for (std::size_t r = 1; r < start.size(); ++r) start[r] += start[r - 1];
  for (std::size_t i = 0; i < src.rank.size(); ++i) {
    if (!src.made[i]) continue;
    std::istringstream in(all.at(start[static_cast<std::size_t>(src.rank[i])]++));
    for (std::string l; std::getline(in, l);) spdlog::info("{}", l);
  }
}

/// Collective: rank src.rank[i] sends bytes_of(i) to every other rank r with needs(i, r);
/// returns, for the items this rank needs from another, their bytes (empty for the others).
std::vector<std::vector<char>> share(
    MPI_Comm comm, const Sources& src, const std::function<bool(std::size_t, int)>& needs,
    const std::function<std::vector<char>(std::size_t)>& bytes_of) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const auto p = static_cast<std::size_t>(size);
  const std::size_t n = src.rank.size();
  std::vector<std::vector<std::vector<char>>> to(p);
  for (std::size_t i = 0; i < n; ++i) {
    if (src.rank[i] != rank) continue;
    std::vector<char> bytes;
    for (int r = 0; r < size; ++r) {
      if (r == rank || !needs(i, r)) continue;
      if (bytes.empty()) bytes = bytes_of(i);
      to[static_cast<std::size_t>(r)].push_back(bytes);
    }
  }
  std::vector<std::vector<std::vector<char>>> from = farm::exchange_blobs(comm, to);
  std::vector<std::size_t> next(p, 0);
  std::vector<std::vector<char>> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto m = static_cast<std::size_t>(src.rank[i]);
    if (src.rank[i] != rank && needs(i, rank)) out[i] = std::move(from[m].at(next[m]++));
  }
  return out;
}

std::vector<char> saved(const dem::Simulation& sim) {
  common::StateStore s;
  dem::save_simulation(sim, s);
  return s.serialize();
}

dem::Simulation loaded(const std::vector<char>& bytes) {
  return dem::load_simulation(common::StateStore::deserialize(bytes));
}

std::vector<char> saved(const dem::Rve& rve) {
  common::StateStore s;
  rve.save(s);
  return s.serialize();
}

}  // namespace

DemPool::DemPool(Job job, dem::RveParams params, InsituPlan plan)
    : job_(std::move(job)), params_(std::move(params)), plan_(std::move(plan)) {}

const dem::Simulation& DemPool::sample(std::int64_t k) {
  auto it = samples_.find(k);
  if (it == samples_.end()) {
    add_sample(k, prepared_sample(job_, k));
    it = samples_.find(k);
  }
  return it->second;
}

void DemPool::add_sample(std::int64_t k, dem::Simulation sim) {
  if (!d50_set_) {
    // Of the PSD for a pool (the same for every sample), else of the one packing's radii.
    const dem::Packing pk{sim.cell(), sim.spheres().x, sim.spheres().r};
    params_.d50 = dem_d50(job_, pk);
    d50_set_ = true;
  }
  samples_.emplace(k, std::move(sim));
}

const dem::Rve& DemPool::get(std::int64_t id) {
  const Key key{plan_.group_of(id), sample_of(id, plan_.options)};
  auto it = rves_.find(key);
  if (it != rves_.end()) return *it->second;
  dem::Simulation sim = sample(key.second);
  if (key.first >= 0) spdlog::info("{}", prepare_group(sim, key));
  return add_rve(key, std::move(sim));
}

const dem::Rve& DemPool::add_rve(const Key& key, dem::Simulation sim) {
  return insert_rve(key,
                    std::make_unique<dem::Rve>(dem::Rve::from_simulation(std::move(sim), params_)));
}

const dem::Rve& DemPool::insert_rve(const Key& key, std::unique_ptr<dem::Rve> made) {
  const auto& rve = *rves_.emplace(key, std::move(made)).first->second;
  if (rves_.size() == 1) {
    spdlog::info("RVE prototype: {} spheres, d50 = {:.4g} m, I = {:.3g}, p_floor = {:.4g} Pa",
                 rve.num_spheres(), rve.d50(), rve.params().inertial_number, rve.params().p_floor);
  }
  return rve;
}

std::string DemPool::prepare_group(dem::Simulation& sim, const Key& key) const {
  const auto [g, k] = key;
  dem::StressTarget t;
  t.stress = plan_.groups.target[static_cast<std::size_t>(g)];
  t.stress_tol = plan_.options.stress_tolerance;
  t.unbalanced_tol = job_.number("dem.preparation.unbalanced_force");
  // The quasi-static rate bound of the preparation, at the target's pressure.
  t.max_rate = dem::strain_rate(job_.number("dem.preparation.inertial_number"), params_.d50,
                                job_.number("dem.material.density"), -t.stress.trace() / 3.0);
  const auto start = std::chrono::steady_clock::now();
  std::int64_t steps = 0;
  try {
    steps = dem::reach_stress(sim, t);
  } catch (const common::NumericalError& e) {
    throw common::NumericalError(
        fmt::format("in-situ preparation of group {} (sample {}): {}", g, k, e.what()));
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const dem::Measures m = dem::measure(sim);
  return fmt::format(
      "in-situ preparation: group {} ({} points), sample {}: {} DEM steps, {:.2f} s; target {}, "
      "reached {}, e = {:.4f}, unbalanced {:.3g}",
      g, plan_.groups.count[static_cast<std::size_t>(g)], k, steps, wall, stress_text(t.stress),
      stress_text(m.stress), m.void_ratio, m.unbalanced);
}

// long-function: one collective sequence (what each rank lacks and holds, then the
// samples, then the group RVEs, each made, shared and agreed on) that every rank runs in the same
// order; kept in one piece so that the order of the collectives is read in one place.
void DemPool::prepare(const std::vector<std::int64_t>& ids, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);

  // What each rank lacks (the RVEs of its points) and holds (its RVEs and samples).
  std::set<Key> lack;
  for (const std::int64_t id : ids) {
    const Key key{plan_.group_of(id), sample_of(id, plan_.options)};
    if (rves_.count(key) == 0) lack.insert(key);
  }
  std::set<Key> held;
  for (const auto& [key, rve] : rves_)
    if (key.first >= 0) held.insert(key);
  std::set<Key> held_samples;  // (-1, k)
  for (const auto& [k, sim] : samples_) held_samples.insert({-1, k});
  const std::vector<std::set<Key>> lacks = allgather_keys(comm, lack);
  const std::vector<std::set<Key>> holds = allgather_keys(comm, held);
  const std::vector<std::set<Key>> sample_holds = allgather_keys(comm, held_samples);

  // The group RVEs some rank lacks, each from its lowest holder or made round robin.
  std::set<Key> group_set;
  for (const auto& l : lacks)
    for (const Key& k : l)
      if (k.first >= 0) group_set.insert(k);
  const std::vector<Key> groups(group_set.begin(), group_set.end());
  const Sources group_src = sources(groups, holds);

  // The samples each rank lacks: for its points without a target and for the groups it makes.
  std::set<Key> sample_lack;
  for (const Key& k : lack)
    if (k.first < 0 && samples_.count(k.second) == 0) sample_lack.insert(k);
  for (std::size_t j = 0; j < groups.size(); ++j) {
    if (group_src.made[j] && group_src.rank[j] == rank && samples_.count(groups[j].second) == 0)
      sample_lack.insert({-1, groups[j].second});
  }
  const std::vector<std::set<Key>> sample_lacks = allgather_keys(comm, sample_lack);
  std::set<Key> sample_set;
  for (const auto& l : sample_lacks) sample_set.insert(l.begin(), l.end());
  const std::vector<Key> ks(sample_set.begin(), sample_set.end());
  const Sources sample_src = sources(ks, sample_holds);

  // 1. The samples: made (on the maker's threads) or held, sent to the ranks that lack them.
  std::vector<std::size_t> my_items;
  for (std::size_t i = 0; i < ks.size(); ++i)
    if (sample_src.made[i] && sample_src.rank[i] == rank) my_items.push_back(i);
  std::vector<std::optional<dem::Simulation>> made(ks.size());
  std::vector<std::vector<std::string>> lines;
  Failure f = in_parallel(
      my_items.size(),
      [&](std::size_t j, std::vector<std::string>& out) {
        const std::size_t i = my_items[j];
        made[i] = prepared_sample(job_, ks[i].second, &out);
      },
      lines);
  farm::agree_on_errors(comm, f.kind, f.message);
  log_in_order(comm, sample_src, lines);
  std::vector<std::vector<char>> got = share(
      comm, sample_src,
      [&](std::size_t i, int r) {
        return sample_lacks[static_cast<std::size_t>(r)].count(ks[i]) != 0;
      },
      [&](std::size_t i) { return saved(made[i] ? *made[i] : samples_.at(ks[i].second)); });
  try {
    for (std::size_t i = 0; i < ks.size(); ++i) {
      if (sample_lack.count(ks[i]) == 0) continue;
      add_sample(ks[i].second, made[i] ? std::move(*made[i]) : loaded(got[i]));
    }
  } catch (const std::exception& e) {
    f = Failure{farm::current_error_kind(),
                std::string("receiving a prepared sample: ") + e.what()};
  }
  farm::agree_on_errors(comm, f.kind, f.message);
  made.clear();
  got.clear();

  // 2. The (group, sample) RVEs: made or held, sent (Rve::save) to the ranks whose points need
  // them.
  my_items.clear();
  for (std::size_t j = 0; j < groups.size(); ++j)
    if (group_src.made[j] && group_src.rank[j] == rank) my_items.push_back(j);
  std::vector<std::unique_ptr<dem::Rve>> built(groups.size());
  f = in_parallel(
      my_items.size(),
      [&](std::size_t n, std::vector<std::string>& out) {
        const std::size_t j = my_items[n];
        dem::Simulation sim = samples_.at(groups[j].second);
        out.push_back(prepare_group(sim, groups[j]));
        built[j] = std::make_unique<dem::Rve>(dem::Rve::from_simulation(std::move(sim), params_));
      },
      lines);
  farm::agree_on_errors(comm, f.kind, f.message);
  log_in_order(comm, group_src, lines);
  got = share(
      comm, group_src,
      [&](std::size_t j, int r) {
        return lacks[static_cast<std::size_t>(r)].count(groups[j]) != 0;
      },
      [&](std::size_t j) { return saved(built[j] ? *built[j] : *rves_.at(groups[j])); });
  try {
    for (std::size_t j = 0; j < groups.size(); ++j) {
      if (lack.count(groups[j]) == 0) continue;
      insert_rve(groups[j], built[j] ? std::move(built[j])
                                     : std::make_unique<dem::Rve>(dem::Rve::load(
                                           common::StateStore::deserialize(got[j]))));
    }
  } catch (const std::exception& e) {
    f = Failure{farm::current_error_kind(), std::string("receiving a prepared RVE: ") + e.what()};
  }
  farm::agree_on_errors(comm, f.kind, f.message);
}

}  // namespace app
