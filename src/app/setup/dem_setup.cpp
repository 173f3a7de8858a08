// Job -> dem parameters and the prepared sample: see dem_setup.hpp.
#include "app/setup/dem_setup.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>

#include "app/job/schema_params.hpp"
#include "app/run/progress.hpp"
#include "common/errors.hpp"
#include "dem/element_test.hpp"
#include "dem/measures.hpp"
#include "dem/packing_io.hpp"

namespace app {

dem::Material dem_material(const Job& job) {
  dem::Material m;
  fill_from_job(job, dem::kMaterial, m);
  fill_from_job(job, dem::kCohFrict, m);
  fill_choices_from_job(job, dem::kMaterialChoices, m);
  dem::for_each_table_law([&](const auto& d) {
    if (m.law == d.kind) fill_from_job(job, d.table, m.*d.params);
  });
  m.validate();
  return m;
}

dem::Numerics dem_numerics(const Job& job) {
  dem::Numerics n;
  fill_from_job(job, dem::kNumerics, n);
  n.validate();
  return n;
}

dem::Preparation dem_preparation(const Job& job) {
  dem::Preparation p;
  fill_from_job(job, dem::kPreparation, p);
  fill_from_job(job, dem::kPreparationTarget, p.target);
  return p;
}

dem::LoadingProgramme dem_loading(const Job& job) {
  dem::LoadingProgramme l;
  fill_choices_from_job(job, dem::kLoadingChoices, l);
  return l;
}

dem::Packing dem_packing(const Job& job, bool& generated, std::int64_t sample) {
  if (job.has("dem.sample.packing")) {
    MPMXDEM_CHECK(sample == 0, "a pool of samples is generated, not read");
    generated = false;
    std::filesystem::path path(job.text("dem.sample.packing"));
    if (path.is_relative()) path = std::filesystem::path(job.directory()) / path;
    std::optional<common::Vec3> cell;
    if (job.has("dem.sample.cell")) {
      const auto& c = job.numbers("dem.sample.cell");
      cell = common::Vec3(c[0], c[1], c[2]);
    }
    return dem::read_packing(path.string(), cell);
  }
  generated = true;
  dem::Psd psd;
  psd.diameter = job.numbers("dem.sample.psd_diameters");
  psd.passing = job.numbers("dem.sample.psd_passing");
  return dem::make_cloud(psd, job.integer("dem.sample.spheres"), 0.3,
                         static_cast<std::uint64_t>(job.integer("dem.sample.seed") + sample));
}

double dem_d50(const Job& job, const dem::Packing& packing) {
  if (job.has("dem.sample.psd_diameters")) {
    // Linear interpolation of the passing curve at 0.5.
    const auto& d = job.numbers("dem.sample.psd_diameters");
    const auto& f = job.numbers("dem.sample.psd_passing");
    for (std::size_t i = 1; i < d.size(); ++i) {
      if (f[i] >= 0.5) return d[i - 1] + (d[i] - d[i - 1]) * (0.5 - f[i - 1]) / (f[i] - f[i - 1]);
    }
    return d.back();
  }
  // Mass median of the packing's spheres.
  std::vector<std::pair<double, double>> rm;  // radius, mass weight r^3
  double total = 0.0;
  for (double r : packing.r) {
    rm.emplace_back(r, r * r * r);
    total += r * r * r;
  }
  std::sort(rm.begin(), rm.end());
  double acc = 0.0;
  for (const auto& [r, w] : rm) {
    acc += w;
    if (acc >= 0.5 * total) return 2.0 * r;
  }
  return rm.empty() ? 0.0 : 2.0 * rm.back().first;
}

namespace {
// Why a generated sample did not reach dem.preparation.void_ratio (dem::Prepared::reached).
std::string void_ratio_rule(const dem::Preparation& prep, const dem::Prepared& done) {
  if (done.compactions == 1) {
    return fmt::format(
        "the compaction at dem.preparation.friction_angle = {:.4g} deg already gives a denser "
        "packing (e = {:.4f}): the search lowers the friction from there, so raise friction_angle "
        "or the target",
        prep.friction_comp_deg, done.compacted_void_ratio);
  }
  return fmt::format(
      "none of {} compactions of the cloud between 0 and {:.4g} deg of friction came within "
      "dem.preparation.void_ratio_tolerance = {:.4g} (the closest: e = {:.4f} at {:.4g} deg): a "
      "target denser than the frictionless compaction, or a tolerance tighter than the scatter "
      "of this sample's compactions",
      done.compactions, prep.friction_comp_deg, prep.void_ratio_tol, done.compacted_void_ratio,
      done.friction_deg);
}
}  // namespace

dem::Simulation prepared_sample(const Job& job, std::int64_t sample,
                                std::vector<std::string>* lines) {
  auto say = [lines](std::string line) {
    if (lines != nullptr) {
      lines->push_back(std::move(line));
    } else {
      spdlog::info("{}", line);
    }
  };
  bool generated = false;
  const dem::Packing packing = dem_packing(job, generated, sample);
  // prepare / equilibrate run with the fixed skin (dem::FixedSkinScope): the prepared sample does
  // not depend on dem.numerics.verlet_skin_min, which applies to what follows.
  dem::Simulation sim = dem::make_simulation(packing, dem_material(job), dem_numerics(job));
  dem::Preparation prep = dem_preparation(job);
  // Strain-rate bound of the servo from the inertial number: I / t_ref, t_ref = d50 sqrt(rho / p).
  prep.compaction_rate =
      dem::strain_rate(job.number("dem.preparation.inertial_number"), dem_d50(job, packing),
                       job.number("dem.material.density"), prep.target.pressure);
  prep.target.max_rate = prep.compaction_rate;
  std::int64_t steps = 0;
  // A line every 10 s: preparation can take minutes (a 30,000-sphere compaction) and has no end
  // known in advance, so the line says where it stands instead of an ETA.
  const auto start = std::chrono::steady_clock::now();
  auto last = start;
  const dem::CheckObserver observe = [&](const dem::Simulation& s, const dem::Measures& m) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last < std::chrono::seconds(10)) return;
    last = now;
    spdlog::info(
        "preparation{}: {} DEM steps, p = {:.4g} of {:.4g} Pa, e = {:.4f}, Z = {:.3f}, "
        "unbalanced {:.3g}, elapsed {}",
        lines != nullptr ? fmt::format(" of sample {}", sample) : "", s.steps(), m.p,
        prep.target.pressure, m.void_ratio, m.z, m.unbalanced,
        Progress::clock(std::chrono::duration<double>(now - start).count()));
  };
  if (generated) {
    say(fmt::format(
        "sample: {} spheres generated (seed {}); compaction to p = {:.4g} Pa with friction {} deg",
        packing.r.size(), job.integer("dem.sample.seed") + sample, prep.target.pressure,
        prep.friction_comp_deg));
    const dem::Prepared done = dem::prepare(sim, prep, observe);
    steps = done.steps;
    if (prep.void_ratio > 0.0) {
      if (!done.reached)
        throw common::InputError(
            job.message("dem.preparation.void_ratio", void_ratio_rule(prep, done)));
      say(
          fmt::format("sample: void ratio {:.4f} (target {:.4g} +/- {:.3g}) at compaction friction "
                      "{:.4g} deg, compaction {} of the search",
                      done.compacted_void_ratio, prep.void_ratio, prep.void_ratio_tol,
                      done.friction_deg, done.compactions));
    }
  } else {
    say(fmt::format("sample: {} spheres read from {}; re-equilibration at p = {:.4g} Pa",
                    packing.r.size(), job.text("dem.sample.packing"), prep.target.pressure));
    steps = dem::equilibrate(sim, prep.target, observe);
  }
  const dem::Measures m = dem::measure(sim);
  say(fmt::format(
      "prepared in {} DEM steps: p = {:.5g} Pa, q = {:.4g} Pa, e = {:.4f}, Z = {:.3f} (without "
      "rattlers {:.3f}), "
      "unbalanced {:.3g}, dt = {:.4g} s",
      steps, m.p, m.q, m.void_ratio, m.z, m.z_mech, m.unbalanced, sim.dt()));
  return sim;
}

}  // namespace app
