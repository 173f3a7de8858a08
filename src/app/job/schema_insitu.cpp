// Job-file keys of the in-situ initial states of DEM points (issue 15, app/setup/insitu.hpp): per
// body initial_state, k0, surface; [dem.initial_state] (floor, grouping, servo tolerance, sample
// pool); and their cross-key rules (check_insitu_rules, called by check_job_rules).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "app/job/job.hpp"
#include "app/job/schema.hpp"
#include "app/job/schema_params.hpp"
#include "app/setup/insitu.hpp"
#include "app/setup/mpm_setup.hpp"

namespace app {

namespace {
// The body keys go right after the last key of [[mpm.body]], so that docs/reference/jobs.md lists
// them in that table.
void add_body_keys(Schema& s) {
  using Q = Quantity;
  Schema b;
  b.add("mpm.body[].initial_state", Type::String,
        "material = \"dem\": initial state of the RVEs; absent: prepared (every RVE a copy of the "
        "isotropic prepared sample); uniform: initial_stress; geostatic: from gravity, density "
        "and k0 (docs/design/dem.md, In-situ initial states). material = \"elastic\": geostatic "
        "only (absent: initial_stress, or zero).")
      .one_of(kInitialStateNames);
  b.add("mpm.body[].k0", Type::Float,
        "initial_state = \"geostatic\": lateral over vertical stress K0 (sigma_h = K0 sigma_v).")
      .in(0, std::nullopt, true);
  b.add("mpm.body[].surface", Type::Float,
        "initial_state = \"geostatic\": level of the free surface along -gravity (the coordinate "
        "x . u, u = -gravity / norm(gravity): z for gravity along -z); absent: the top of the "
        "body's box.")
      .unit(Q::Length);
  std::size_t last = 0;
  for (std::size_t i = 0; i < s.keys.size(); ++i) {
    if (s.keys[i].path.starts_with("mpm.body[]")) last = i + 1;
  }
  s.keys.insert(s.keys.begin() + static_cast<std::ptrdiff_t>(last), b.keys.begin(), b.keys.end());
}

// The pool of samples: generated, and drawn scattered only from more than one.
void pool_rules(const Job& job, std::vector<std::string>& err) {
  const bool pool =
      job.has("dem.initial_state.samples") && job.integer("dem.initial_state.samples") > 1;
  if (pool && job.has("dem.sample.packing")) {
    err.push_back(job.message("dem.initial_state.samples",
                              "a pool of samples is generated (seeds seed, seed + 1, ...): not "
                              "with dem.sample.packing, one given packing"));
  }
  // A scattered draw from one sample is asked for in vain; in_turn is the default, which the
  // resolved job writes whatever the pool.
  if (written(job, "dem.initial_state.sample_draw") &&
      choice_of(job, "dem.initial_state.sample_draw", kSampleDrawNames) == SampleDraw::scattered &&
      !pool) {
    err.push_back(job.message("dem.initial_state.sample_draw",
                              "only with dem.initial_state.samples > 1 (with one sample every "
                              "point draws it)"));
  }
}
}  // namespace

void add_insitu_sections(Schema& s) {
  add_body_keys(s);
  for (Key& k : s.keys) {
    if (k.path == "mpm.body[].initial_stress") {
      k.doc =
          "Initial Cauchy stress xx, yy, zz, yz, xz, xy (tension positive); dem: only with "
          "initial_state = \"uniform\" (the RVEs' target).";
    }
  }
  s.add("dem.initial_state", Type::Table,
        "In-situ initial states of DEM bodies (mpm.body[].initial_state): pressure floor, grouping "
        "of the targets, servo tolerance and the pool of samples.");
  s.add("dem.initial_state.pressure_floor", Type::Float,
        "Targets whose p is below this are scaled up to it (points near a free surface); the "
        "log reports how many.")
      .unit(Quantity::Pressure)
      .in(0, std::nullopt, true)
      .or_default(1e3);
  s.add("dem.initial_state.group_tolerance", Type::Float,
        "Targets within this fraction of max(p, pressure_floor) on every component share one "
        "preparation (0: only equal targets).")
      .in(0, 1, false, true)
      .or_default(0.02);
  s.add("dem.initial_state.stress_tolerance", Type::Float,
        "Servo tolerance: each diagonal component within this fraction of itself, off-diagonal "
        "ones within this fraction of p.")
      .in(0, 1, true, true)
      .or_default(0.01);
  s.add("dem.initial_state.samples", Type::Int,
        "Pool of independently generated samples (seeds seed, seed + 1, ...); point id draws "
        "one of them as sample_draw says. 1: every RVE from the one sample.")
      .in(1, 1000)
      .or_default(std::int64_t{1});
  s.add("dem.initial_state.sample_draw", Type::String,
        "How point id draws its sample: in_turn, id mod samples (points are numbered row by "
        "row, x fastest: when a row's length is a multiple of samples, each vertical line of "
        "points has one sample); scattered, a hash of id and dem.sample.seed mod samples (no "
        "pattern in space; another seed, another draw).")
      .one_of(kSampleDrawNames)
      .or_default(std::string("in_turn"));
}

std::vector<std::string> check_insitu_rules(const Job& job) {
  std::vector<std::string> err;
  for (std::size_t b = 0; b < job.count("mpm.body"); ++b) {
    const std::string base = fmt::format("mpm.body[{}].", b);
    const bool dem = choice_of(job, base + "material", kBodyMaterialNames) == kDemMaterial;
    const InitialState state =
        choice_of(job, base + "initial_state", kInitialStateNames, InitialState::prepared);
    if (!dem && job.has(base + "initial_state") && state != InitialState::geostatic) {
      err.push_back(job.message(base + "initial_state",
                                "an elastic body takes initial_state = \"geostatic\" only "
                                "(otherwise it starts from initial_stress)"));
      continue;
    }
    if (!dem && state == InitialState::geostatic && job.has(base + "initial_stress")) {
      err.push_back(job.message(base + "initial_stress",
                                "not with initial_state = \"geostatic\" (the initial stress "
                                "comes from gravity, density and k0)"));
    }
    if (dem && job.has(base + "initial_stress") && state != InitialState::uniform) {
      err.push_back(job.message(base + "initial_stress",
                                "used with material = \"dem\" only when initial_state = "
                                "\"uniform\" (otherwise the initial stress is the RVEs' own)"));
    }
    if (state == InitialState::uniform) {
      if (!job.has(base + "initial_stress")) {
        err.push_back(job.missing_message(base + "initial_stress",
                                          "required when initial_state = \"uniform\""));
      } else {
        const auto& v = job.numbers(base + "initial_stress");
        if (!(-(v[0] + v[1] + v[2]) / 3.0 > 0.0)) {
          err.push_back(job.message(base + "initial_stress",
                                    "initial_state = \"uniform\" needs a compressive mean stress "
                                    "(p = -(xx + yy + zz) / 3 > 0, tension positive): a packing "
                                    "holds no tension"));
        }
      }
    }
    for (const char* k : {"k0", "surface"}) {
      if (job.has(base + k) && state != InitialState::geostatic) {
        err.push_back(job.message(base + k, "only with initial_state = \"geostatic\""));
      }
    }
    if (state == InitialState::geostatic) {
      if (!job.has(base + "k0")) {
        err.push_back(
            job.missing_message(base + "k0", "required when initial_state = \"geostatic\""));
      }
      bool gravity = job.has("mpm.gravity");
      double g2 = 0.0;  // |g|^2 as the set-up computes it: 0 or inf when it under- or overflows
      if (gravity) {
        const auto& g = job.numbers("mpm.gravity");
        gravity = std::any_of(g.begin(), g.end(), [](double x) { return x != 0.0; });
        for (const double x : g) g2 += x * x;
      }
      if (!gravity) {
        err.push_back(job.message(base + "initial_state",
                                  "initial_state = \"geostatic\" needs a non-zero mpm.gravity"));
      } else if (!std::isnormal(g2) || !std::isnormal(std::sqrt(g2))) {
        err.push_back(job.message(
            "mpm.gravity", "its magnitude squared (" + fmt::format("{}", g2) +
                               " m^2/s^4) under- or overflows double precision: initial_state = "
                               "\"geostatic\" divides by it (gravity in m/s^2?)"));
      }
    }
  }
  pool_rules(job, err);
  return err;
}

}  // namespace app
