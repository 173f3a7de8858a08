// Job -> farm::CoupledConfig: see coupled_setup.hpp.
#include "app/coupled_setup.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "app/dem_setup.hpp"
#include "app/insitu.hpp"
#include "app/mpm_setup.hpp"
#include "app/schema_params.hpp"
#include "common/errors.hpp"
#include "dem/element_test.hpp"
#include "dem/measures.hpp"
#include "dem/stress_target.hpp"
#include "farm/dem_micro.hpp"
#include "farm/elastic_micro.hpp"
#include "farm/spared_micro.hpp"

namespace app {

namespace {

farm::ElasticMicroParams elastic_params(const Job& job, const MpmSetup& setup,
                                        const std::set<std::int64_t>& dem_ids) {
  farm::ElasticMicroParams p;
  p.young = job.number("mpm.elastic.young_modulus");
  p.poisson = job.number("mpm.elastic.poisson_ratio");
  // The wave speed (CFL) uses the lightest elastic body: the fastest waves.
  p.density = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < setup.points.size(); ++i) {
    if (dem_ids.count(setup.points.id[i]) == 0) {
      p.density = std::min(p.density, setup.points.mass[i] / setup.points.volume[i]);
    }
  }
  p.initial_stress = setup.elastic_initial_stress;
  p.validate();
  return p;
}

dem::RveParams rve_params(const Job& job) {
  dem::RveParams p;
  p.material = dem_material(job);
  p.numerics = dem_numerics(job);
  fill_from_job(job, dem::kRveParams, p);
  p.carry_end_forces = job.text("dem.coupling.end_forces") == "carried";
  p.initial_pressure = 0.0;  // the prototype is prepared by prepared_sample()
  p.validate();
  return p;
}

/// The DEM RVEs of a rank, made on first use: the prepared sample of each sample of the pool
/// (the preparation of [dem.sample]), and one RVE per (group, sample) that the rank's points
/// need, brought by the tensor servo to the group's target (app/insitu.hpp). Every RVE of a
/// point is a copy of its (group, sample) RVE. With the defaults (prepared bodies, one sample)
/// this is the one prepared sample of before, unchanged.
struct DemPool {
  Job job;
  dem::RveParams params;
  InsituPlan plan;
  std::map<std::int64_t, dem::Simulation> samples;
  std::map<std::pair<std::int32_t, std::int64_t>, std::unique_ptr<dem::Rve>> rves;

  const dem::Simulation& sample(std::int64_t k) {
    auto it = samples.find(k);
    if (it == samples.end()) {
      dem::Simulation sim = prepared_sample(job, k);
      if (samples.empty()) {
        const dem::Packing pk{sim.cell(), sim.spheres().x, sim.spheres().r};
        params.d50 = dem_d50(job, pk);  // of the PSD for a pool (the same for every sample)
      }
      it = samples.emplace(k, std::move(sim)).first;
    }
    return it->second;
  }

  const dem::Rve& get(std::int64_t id) {
    const std::int32_t g = plan.group_of(id);
    const std::int64_t k = sample_of(id, plan.options.samples);
    const auto key = std::make_pair(g, k);
    auto it = rves.find(key);
    if (it != rves.end()) return *it->second;
    dem::Simulation sim = sample(k);
    if (g >= 0) spdlog::info("{}", prepare_group(sim, g, k));
    return add_rve(key, std::move(sim));
  }

  const dem::Rve& add_rve(const std::pair<std::int32_t, std::int64_t>& key, dem::Simulation sim) {
    const auto& rve =
        *rves.emplace(key,
                      std::make_unique<dem::Rve>(dem::Rve::from_simulation(std::move(sim), params)))
             .first->second;
    if (rves.size() == 1) {
      spdlog::info("RVE prototype: {} spheres, d50 = {:.4g} m, I = {:.3g}, p_floor = {:.4g} Pa",
                   rve.num_spheres(), params.d50, params.inertial_number, params.p_floor);
    }
    return rve;
  }

  /// Makes ahead, on this rank's threads, the samples and the (group, sample) RVEs that the
  /// points `ids` need and that are not made yet: each preparation on one thread (the DEM is
  /// the same bits on any number of threads, so the RVEs are those get() would make one by
  /// one), their log lines in (sample, group) order afterwards, the first failure in that
  /// order rethrown.
  void prepare(const std::vector<std::int64_t>& ids) {
    std::set<std::int64_t> new_samples;
    std::set<std::pair<std::int32_t, std::int64_t>> new_rves;
    for (const std::int64_t id : ids) {
      const std::int32_t g = plan.group_of(id);
      const std::int64_t k = sample_of(id, plan.options.samples);
      if (samples.count(k) == 0) new_samples.insert(k);
      if (g >= 0 && rves.count({g, k}) == 0) new_rves.insert({g, k});
    }
    const std::vector<std::int64_t> ks(new_samples.begin(), new_samples.end());
    std::vector<std::optional<dem::Simulation>> made(ks.size());
    in_parallel(ks.size(), [&](std::size_t i, std::vector<std::string>& lines) {
      made[i] = prepared_sample(job, ks[i], &lines);
    });
    for (std::size_t i = 0; i < ks.size(); ++i) {
      if (samples.empty()) {
        const dem::Packing pk{made[i]->cell(), made[i]->spheres().x, made[i]->spheres().r};
        params.d50 = dem_d50(job, pk);
      }
      samples.emplace(ks[i], std::move(*made[i]));
    }
    const std::vector<std::pair<std::int32_t, std::int64_t>> keys(new_rves.begin(), new_rves.end());
    std::vector<std::optional<dem::Simulation>> grouped(keys.size());
    in_parallel(keys.size(), [&](std::size_t i, std::vector<std::string>& lines) {
      dem::Simulation sim = samples.at(keys[i].second);
      lines.push_back(prepare_group(sim, keys[i].first, keys[i].second));
      grouped[i] = std::move(sim);
    });
    for (std::size_t i = 0; i < keys.size(); ++i) add_rve(keys[i], std::move(*grouped[i]));
  }

  /// Runs job(i, lines) for i < n on the rank's threads (dynamic, one at a time: preparations
  /// differ in cost), then logs each job's lines in the order of i and rethrows the first
  /// failure in that order.
  static void in_parallel(std::size_t n,
                          const std::function<void(std::size_t, std::vector<std::string>&)>& job) {
    std::vector<std::vector<std::string>> lines(n);
    std::vector<std::exception_ptr> failed(n);
    const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(dynamic, 1) if (n > 1)
    for (std::int64_t i = 0; i < count; ++i) {
      const auto u = static_cast<std::size_t>(i);
      try {
        job(u, lines[u]);
      } catch (...) {
        failed[u] = std::current_exception();
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (failed[i]) std::rethrow_exception(failed[i]);
      for (const std::string& line : lines[i]) spdlog::info("{}", line);
    }
  }

  /// Brings a copy of sample k to the target of group g (tensor servo); returns the log line
  /// with its cost.
  [[nodiscard]] std::string prepare_group(dem::Simulation& sim, std::int32_t g,
                                          std::int64_t k) const {
    dem::StressTarget t;
    t.stress = plan.groups.target[static_cast<std::size_t>(g)];
    t.stress_tol = plan.options.stress_tolerance;
    t.unbalanced_tol = job.number("dem.preparation.unbalanced_force");
    // The quasi-static rate bound of the preparation, at the target's pressure.
    t.max_rate = dem::strain_rate(job.number("dem.preparation.inertial_number"), params.d50,
                                  job.number("dem.material.density"), -t.stress.trace() / 3.0);
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
        g, plan.groups.count[static_cast<std::size_t>(g)], k, steps, wall, stress_text(t.stress),
        stress_text(m.stress), m.void_ratio, m.unbalanced);
  }
};

/// The plan in the log (every rank computes it; rank 0 writes it).
void log_plan(const InsituPlan& plan) {
  const std::size_t n = plan.ids.size();
  const auto prepared =
      static_cast<std::size_t>(std::count(plan.group.begin(), plan.group.end(), -1));
  if (prepared == n && plan.options.samples == 1) return;  // today's single prepared sample
  spdlog::info(
      "in-situ initial states: {} DEM points, {} as prepared, {} in {} group(s) of targets "
      "(tolerance {:g}), {} floored to p = {:.4g} Pa; {} sample(s): {} preparation(s)",
      n, prepared, n - prepared, plan.groups.target.size(), plan.options.group_tolerance,
      plan.floored, plan.options.pressure_floor, plan.options.samples, plan.preparations());
  constexpr std::size_t kShown = 40;
  for (std::size_t g = 0; g < plan.groups.target.size() && g < kShown; ++g) {
    spdlog::info("  group {}: {} points, target {}", g, plan.groups.count[g],
                 stress_text(plan.groups.target[g]));
  }
  if (plan.groups.target.size() > kShown)
    spdlog::info("  ... {} more groups", plan.groups.target.size() - kShown);
}

farm::MicroKind micro_kind(const Job& job, const MpmSetup& setup,
                           const std::set<std::int64_t>& dem_ids, InsituPlan plan) {
  std::shared_ptr<DemPool> proto;
  if (setup.has_dem) {
    log_plan(plan);
    proto = std::make_shared<DemPool>(DemPool{job, rve_params(job), std::move(plan), {}, {}});
  }
  std::shared_ptr<farm::ElasticMicroParams> elastic;
  if (setup.has_elastic)
    elastic = std::make_shared<farm::ElasticMicroParams>(elastic_params(job, setup, dem_ids));
  const std::uint32_t fail_guards = farm::DemMicroParams{}.fail_guards;

  farm::MicroKind k;
  k.create = [proto, elastic, dem_ids,
              fail_guards](std::int64_t id) -> std::unique_ptr<farm::MicroModel> {
    if (dem_ids.count(id) != 0)
      return std::make_unique<farm::DemMicro>(proto->get(id), fail_guards);
    return std::make_unique<farm::ElasticMicro>(id, *elastic);
  };
  k.load = [](const common::StateReader& r) -> std::unique_ptr<farm::MicroModel> {
    if (r.has("elastic/id")) return farm::ElasticMicro::load(r);
    return farm::DemMicro::load(r);
  };
  if (proto) {
    k.prepare = [proto, dem_ids](const std::vector<std::int64_t>& ids) {
      std::vector<std::int64_t> dem;
      for (const std::int64_t id : ids)
        if (dem_ids.count(id) != 0) dem.push_back(id);
      proto->prepare(dem);
    };
  }
  return k;
}

}  // namespace

farm::CoupledConfig coupled_setup(const Job& job, const RunLimits& limits) {
  MpmSetup setup = mpm_setup(job);
  farm::CoupledConfig c;
  InsituPlan plan;
  if (setup.has_dem) plan = insitu_plan(job, setup);  // before the materials are reset below
  std::set<std::int64_t> dem_ids;
  for (std::size_t i = 0; i < setup.points.size(); ++i) {
    if (setup.points.material[i] == kDemMaterial) dem_ids.insert(setup.points.id[i]);
    setup.points.material[i] = 0;  // the farm is the one material; it dispatches by point id
  }
  // [dem.sparing]: the DEM RVEs wrapped in farm::SparedMicro when its tolerance is > 0.
  farm::SparingOptions sparing;
  fill_from_job(job, farm::kSparingOptions, sparing);
  if (setup.has_dem) sparing.pressure_floor = job.number("dem.coupling.pressure_floor");
  if (sparing.tolerance > 0.0 && setup.has_dem) {
    spdlog::info("sparing idle RVEs: tolerance {:g}, at most {} spared steps, drift tolerance {:g}",
                 sparing.tolerance, sparing.max_spared_steps, sparing.drift_tolerance);
  }
  c.micro = farm::spared_kind(micro_kind(job, setup, dem_ids, std::move(plan)), sparing,
                              farm::is_dem_micro, farm::dem_micro_tangent);
  c.solver = setup.config;
  c.points = std::move(setup.points);
  c.constraints = std::move(setup.constraints);
  c.tractions = std::move(setup.tractions);
  c.end_time = setup.end_time;
  c.max_steps = std::max<std::int64_t>(limits.max_steps, 0);
  c.job_text = job.source_text();

  c.output.dir = limits.out_dir;
  fill_from_job(job, farm::kOutputOptions, c.output);
  if (job.has("output.grains.rves")) {
    // Only DEM RVEs have grains: an id of another material, or of no point, is refused here
    // with the job's line, before anything is written.
    c.grains.rves = job.integers("output.grains.rves");
    c.grains.every = job.integer("output.grains.every");
    std::set<std::int64_t> seen;
    for (std::int64_t id : c.grains.rves) {
      std::string rule;
      if (!seen.insert(id).second) {
        rule = fmt::format("id {} is listed twice", id);
      } else if (dem_ids.count(id) == 0) {
        rule =
            std::find(c.points.id.begin(), c.points.id.end(), id) != c.points.id.end()
                ? fmt::format(
                      "point id {} is not a DEM RVE (its material has no grains to "
                      "draw)",
                      id)
                : fmt::format("no material point has id {} (the job has {} point(s){})", id,
                              c.points.size(),
                              dem_ids.empty() ? ", none of them DEM"
                                              : fmt::format(", DEM RVE ids {}..{}",
                                                            *dem_ids.begin(), *dem_ids.rbegin()));
      }
      if (!rule.empty()) throw common::InputError(job.message("output.grains.rves", rule));
    }
  }
  fill_from_job(job, farm::kCheckpointOptions, c.checkpoint);
  fill_from_job(job, farm::kBalanceOptions, c.balance);
  c.farm.wait = farm::wait_mode_from(job.text("farm.wait"));
  c.farm.rank0_rves = job.flag("farm.rank0_rves");
  c.validate();
  return c;
}

}  // namespace app
