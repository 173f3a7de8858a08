// Job -> farm::CoupledConfig: see coupled_setup.hpp.
#include "app/setup/coupled_setup.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "app/job/schema_params.hpp"
#include "app/setup/dem_pool.hpp"
#include "app/setup/dem_setup.hpp"
#include "app/setup/insitu.hpp"
#include "app/setup/mpm_setup.hpp"
#include "common/errors.hpp"
#include "farm/dem_micro.hpp"
#include "farm/elastic_micro.hpp"
#include "farm/spared_micro.hpp"

namespace app {

namespace {

farm::ElasticMicroParams elastic_params(const Job& job, const MpmSetup& setup,
                                        const std::set<std::int64_t>& dem_ids) {
  farm::ElasticMicroParams p;
  fill_from_job(job, farm::kElasticMaterial, p.material);  // absent angles: 0, no softening
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
  fill_choices_from_job(job, dem::kRveChoices, p);  // end_forces, rate, contact_loss, free_flight
  p.initial_pressure = 0.0;  // the prototype is prepared by prepared_sample()
  p.validate();
  return p;
}

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
    proto = std::make_shared<DemPool>(job, rve_params(job), std::move(plan));
  }
  std::shared_ptr<farm::ElasticMicroParams> elastic;
  std::shared_ptr<const std::map<std::int64_t, common::Mat3>> elastic_s0;
  if (setup.has_elastic) {
    elastic = std::make_shared<farm::ElasticMicroParams>(elastic_params(job, setup, dem_ids));
    elastic_s0 = std::make_shared<const std::map<std::int64_t, common::Mat3>>(
        continuum_initial_stress(job, setup));
  }
  const std::uint32_t fail_guards = farm::DemMicroParams{}.fail_guards;

  farm::MicroKind k;
  k.create = [proto, elastic, elastic_s0, dem_ids,
              fail_guards](std::int64_t id) -> std::unique_ptr<farm::MicroModel> {
    if (dem_ids.count(id) != 0)
      return std::make_unique<farm::DemMicro>(proto->get(id), fail_guards);
    const auto s0 = elastic_s0->find(id);
    if (s0 != elastic_s0->end())
      return std::make_unique<farm::ElasticMicro>(id, *elastic, s0->second);
    return std::make_unique<farm::ElasticMicro>(id, *elastic);
  };
  k.load = [](const common::StateReader& r) -> std::unique_ptr<farm::MicroModel> {
    if (r.has("elastic/id")) return farm::ElasticMicro::load(r);
    return farm::DemMicro::load(r);
  };
  if (proto) {
    k.prepare = [proto, dem_ids](const std::vector<std::int64_t>& ids, MPI_Comm comm) {
      std::vector<std::int64_t> dem;
      for (const std::int64_t id : ids)
        if (dem_ids.count(id) != 0) dem.push_back(id);
      proto->prepare(dem, comm);
    };
  }
  return k;
}

}  // namespace

farm::CoupledConfig coupled_setup(const Job& job, const RunLimits& limits) {
  return coupled_setup(job, mpm_setup(job), limits);
}

farm::CoupledConfig coupled_setup(const Job& job, MpmSetup setup, const RunLimits& limits) {
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
    fill_from_job(job, farm::kGrainViewOptions, c.grains);
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
  fill_choices_from_job(job, farm::kFarmChoices, c.farm);  // wait, partition, rank0_rves
  c.validate();
  return c;
}

}  // namespace app
