// Job -> farm::CoupledConfig: see coupled_setup.hpp.
#include "app/coupled_setup.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <set>

#include "app/dem_setup.hpp"
#include "app/mpm_setup.hpp"
#include "app/schema_params.hpp"
#include "farm/dem_micro.hpp"
#include "farm/elastic_micro.hpp"

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
  p.initial_pressure = 0.0;  // the prototype is prepared by prepared_sample()
  p.validate();
  return p;
}

/// Every DEM RVE of a rank starts as a copy of one prepared sample, made on first use: the
/// preparation (equilibration or compaction) runs once per rank, not once per RVE.
struct DemPrototype {
  Job job;
  dem::RveParams params;
  std::unique_ptr<dem::Rve> rve;

  const dem::Rve& get() {
    if (!rve) {
      dem::Simulation sim = prepared_sample(job);
      const dem::Packing pk{sim.cell(), sim.spheres().x, sim.spheres().r};
      params.d50 = dem_d50(job, pk);
      rve = std::make_unique<dem::Rve>(dem::Rve::from_simulation(std::move(sim), params));
      spdlog::info("RVE prototype: {} spheres, d50 = {:.4g} m, I = {:.3g}, p_floor = {:.4g} Pa",
                   rve->num_spheres(), params.d50, params.inertial_number, params.p_floor);
    }
    return *rve;
  }
};

farm::MicroKind micro_kind(const Job& job, const MpmSetup& setup,
                           const std::set<std::int64_t>& dem_ids) {
  std::shared_ptr<DemPrototype> proto;
  if (setup.has_dem)
    proto = std::make_shared<DemPrototype>(DemPrototype{job, rve_params(job), nullptr});
  std::shared_ptr<farm::ElasticMicroParams> elastic;
  if (setup.has_elastic)
    elastic = std::make_shared<farm::ElasticMicroParams>(elastic_params(job, setup, dem_ids));
  const std::uint32_t fail_guards = farm::DemMicroParams{}.fail_guards;

  farm::MicroKind k;
  k.create = [proto, elastic, dem_ids,
              fail_guards](std::int64_t id) -> std::unique_ptr<farm::MicroModel> {
    if (dem_ids.count(id) != 0) return std::make_unique<farm::DemMicro>(proto->get(), fail_guards);
    return std::make_unique<farm::ElasticMicro>(id, *elastic);
  };
  k.load = [](const common::StateReader& r) -> std::unique_ptr<farm::MicroModel> {
    if (r.has("elastic/id")) return farm::ElasticMicro::load(r);
    return farm::DemMicro::load(r);
  };
  return k;
}

}  // namespace

farm::CoupledConfig coupled_setup(const Job& job, const RunLimits& limits) {
  MpmSetup setup = mpm_setup(job);
  farm::CoupledConfig c;
  std::set<std::int64_t> dem_ids;
  for (std::size_t i = 0; i < setup.points.size(); ++i) {
    if (setup.points.material[i] == kDemMaterial) dem_ids.insert(setup.points.id[i]);
    setup.points.material[i] = 0;  // the farm is the one material; it dispatches by point id
  }
  c.micro = micro_kind(job, setup, dem_ids);
  c.solver = setup.config;
  c.points = std::move(setup.points);
  c.constraints = std::move(setup.constraints);
  c.tractions = std::move(setup.tractions);
  c.end_time = setup.end_time;
  c.max_steps = std::max<std::int64_t>(limits.max_steps, 0);
  c.job_text = job.source_text();

  c.output.dir = limits.out_dir;
  fill_from_job(job, farm::kOutputOptions, c.output);
  fill_from_job(job, farm::kCheckpointOptions, c.checkpoint);
  fill_from_job(job, farm::kBalanceOptions, c.balance);
  c.farm.wait = farm::wait_mode_from(job.text("farm.wait"));
  c.validate();
  return c;
}

}  // namespace app
