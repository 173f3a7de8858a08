// In-situ targets, pressure floor and grouping: see insitu.hpp.
#include "app/setup/insitu.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>

#include "app/job/job.hpp"
#include "app/job/schema_params.hpp"
#include "app/setup/mpm_setup.hpp"
#include "common/errors.hpp"
#include "farm/checksum.hpp"

namespace app {

using common::Mat3;
using common::Vec3;

Mat3 geostatic_stress(double rho, const Vec3& gravity, double k0, double depth) {
  const double g = gravity.norm();
  MPMXDEM_CHECK(g > 0.0, "geostatic stress needs a non-zero gravity");
  const Vec3 e = gravity / g;  // downwards
  const double sv = -rho * g * depth;
  const Mat3 ee = e * e.transpose();
  return sv * ee + k0 * sv * (Mat3::Identity() - ee);
}

double depth_below(const Vec3& x, const Vec3& gravity, double surface) {
  return surface - x.dot(-gravity / gravity.norm());
}

bool apply_pressure_floor(Mat3& target, double floor) {
  const double p = -target.trace() / 3.0;
  MPMXDEM_CHECK(p > 0.0, "a target stress with p > 0");
  if (p >= floor) return false;
  target *= floor / p;
  return true;
}

namespace {
std::array<double, 7> sort_key(const Mat3& s) {
  return {-s.trace() / 3.0, s(0, 0), s(1, 1), s(2, 2), s(1, 2), s(0, 2), s(0, 1)};
}
}  // namespace

Grouping group_targets(const std::vector<Mat3>& targets, double tolerance, double floor) {
  const std::size_t n = targets.size();
  std::vector<std::array<double, 7>> keys(n);
  for (std::size_t i = 0; i < n; ++i) keys[i] = sort_key(targets[i]);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return keys[a] != keys[b] ? keys[a] < keys[b] : a < b;
  });
  Grouping g;
  g.group_of.assign(n, -1);
  for (const std::size_t i : order) {
    if (!g.target.empty()) {
      const Mat3& r = g.target.back();
      const double scale = tolerance * std::max(-r.trace() / 3.0, floor);
      if ((targets[i] - r).cwiseAbs().maxCoeff() <= scale) {
        g.group_of[i] = static_cast<std::int32_t>(g.target.size() - 1);
        ++g.count.back();
        continue;
      }
    }
    g.group_of[i] = static_cast<std::int32_t>(g.target.size());
    g.target.push_back(targets[i]);
    g.count.push_back(1);
  }
  return g;
}

std::int32_t InsituPlan::group_of(std::int64_t id) const {
  const auto it = std::lower_bound(ids.begin(), ids.end(), id);
  MPMXDEM_CHECK(it != ids.end() && *it == id, "the in-situ plan holds every DEM point id");
  return group[static_cast<std::size_t>(it - ids.begin())];
}

std::int64_t sample_of(std::int64_t id, const InsituOptions& o) {
  if (o.draw == SampleDraw::in_turn) return sample_of(id, o.samples);
  const std::uint64_t h = farm::splitmix64(farm::splitmix64(static_cast<std::uint64_t>(id)) ^
                                           static_cast<std::uint64_t>(o.draw_seed));
  return static_cast<std::int64_t>(h % static_cast<std::uint64_t>(o.samples));
}

std::int64_t InsituPlan::preparations() const {
  std::set<std::pair<std::int32_t, std::int64_t>> pairs;
  for (std::size_t i = 0; i < ids.size(); ++i) pairs.emplace(group[i], sample_of(ids[i], options));
  return static_cast<std::int64_t>(pairs.size());
}

namespace {
Mat3 voigt(const std::vector<double>& s) {  // xx, yy, zz, yz, xz, xy
  Mat3 m;
  m << s[0], s[5], s[4], s[5], s[1], s[3], s[4], s[3], s[2];
  return m;
}
/// The geostatic stress of point index i of `setup` (its body has initial_state = "geostatic").
/// Throws common::InputError naming the body's key when it cannot be made.
Mat3 geostatic_target(const Job& job, const MpmSetup& setup, std::size_t i) {
  const mpm::MaterialPoints& pts = setup.points;
  const Vec3 g = setup.config.gravity;
  const std::int64_t id = pts.id[i];
  const std::string base = fmt::format("mpm.body[{}].", setup.body[i]);
  double surface = 0.0;
  if (job.has(base + "surface")) {
    surface = job.number(base + "surface");
  } else {
    const auto& lo = job.numbers(base + "min");
    const auto& hi = job.numbers(base + "max");
    surface = -std::numeric_limits<double>::infinity();
    for (int c = 0; c < 8; ++c) {  // the box corner highest along -gravity
      const Vec3 x((c & 1) != 0 ? hi[0] : lo[0], (c & 2) != 0 ? hi[1] : lo[1],
                   (c & 4) != 0 ? hi[2] : lo[2]);
      surface = std::max(surface, x.dot(-g / g.norm()));
    }
  }
  const double depth = depth_below(pts.x[i], g, surface);
  if (!(depth > 0.0)) {
    throw common::InputError(job.message(
        base + "surface",
        fmt::format("material point id {} at ({}, {}, {}) lies {} m above the free surface: "
                    "a geostatic body lies below its surface",
                    id, pts.x[i][0], pts.x[i][1], pts.x[i][2], -depth)));
  }
  const Mat3 t = geostatic_stress(job.number(base + "density"), g, job.number(base + "k0"), depth);
  if (!t.allFinite()) {
    const bool vertical = std::isfinite(job.number(base + "density") * g.norm() * depth);
    throw common::InputError(job.message(
        base + (vertical ? "k0" : "density"),
        fmt::format("the geostatic stress of material point id {} (depth {} m, density {} "
                    "kg/m^3, |g| {} m/s^2, k0 {}) is not a finite number: the product "
                    "overflows double precision",
                    id, depth, job.number(base + "density"), g.norm(), job.number(base + "k0"))));
  }
  const double p = -t.trace() / 3.0;
  if (pts.material[i] == kDemMaterial && job.has("dem.material.young_modulus") &&
      p > 0.1 * job.number("dem.material.young_modulus")) {
    throw common::InputError(job.message(
        base + "density",
        fmt::format("the geostatic mean stress of material point id {} (depth {} m) is {:.4g} "
                    "Pa, above a tenth of the grains' Young modulus (dem.material.young_modulus "
                    "= {:.4g} Pa): contacts would overlap by about 4 p / E = {:.2g} of the radii",
                    id, depth, p, job.number("dem.material.young_modulus"),
                    4.0 * p / job.number("dem.material.young_modulus"))));
  }
  return t;
}

}  // namespace

InsituPlan insitu_plan(const Job& job, const MpmSetup& setup) {
  InsituPlan plan;
  auto& o = plan.options;
  if (job.has("dem.initial_state.pressure_floor"))
    o.pressure_floor = job.number("dem.initial_state.pressure_floor");
  if (job.has("dem.initial_state.group_tolerance"))
    o.group_tolerance = job.number("dem.initial_state.group_tolerance");
  if (job.has("dem.initial_state.stress_tolerance"))
    o.stress_tolerance = job.number("dem.initial_state.stress_tolerance");
  if (job.has("dem.initial_state.samples")) o.samples = job.integer("dem.initial_state.samples");
  o.draw = choice_of(job, "dem.initial_state.sample_draw", kSampleDrawNames, SampleDraw::in_turn);
  if (job.has("dem.sample.seed")) o.draw_seed = job.integer("dem.sample.seed");

  const mpm::MaterialPoints& pts = setup.points;
  MPMXDEM_CHECK(setup.body.size() == pts.size(), "one body index per point");
  std::vector<std::pair<std::int64_t, std::size_t>> dem_points;  // id, index
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (pts.material[i] == kDemMaterial) dem_points.emplace_back(pts.id[i], i);
  }
  std::sort(dem_points.begin(), dem_points.end());
  std::vector<Mat3> targets;
  std::vector<std::size_t> with_target;  // index into plan.ids
  for (const auto& [id, i] : dem_points) {
    const std::string base = fmt::format("mpm.body[{}].", setup.body[i]);
    const InitialState state =
        choice_of(job, base + "initial_state", kInitialStateNames, InitialState::prepared);
    plan.ids.push_back(id);
    plan.group.push_back(-1);
    Mat3 t = Mat3::Zero();
    if (state == InitialState::uniform) {
      t = voigt(job.numbers(base + "initial_stress"));
    } else if (state == InitialState::geostatic) {
      t = geostatic_target(job, setup, i);
    }
    if (state != InitialState::prepared) {
      if (apply_pressure_floor(t, o.pressure_floor)) ++plan.floored;
      with_target.push_back(plan.ids.size() - 1);
      targets.push_back(t);
    }
    plan.target.push_back(t);
  }
  plan.groups = group_targets(targets, o.group_tolerance, o.pressure_floor);
  for (std::size_t k = 0; k < with_target.size(); ++k)
    plan.group[with_target[k]] = plan.groups.group_of[k];
  return plan;
}

std::map<std::int64_t, Mat3> continuum_initial_stress(const Job& job, const MpmSetup& setup) {
  std::map<std::int64_t, Mat3> out;
  for (std::size_t i = 0; i < setup.points.size(); ++i) {
    if (setup.points.material[i] == kDemMaterial) continue;
    const std::string base = fmt::format("mpm.body[{}].", setup.body[i]);
    if (choice_of(job, base + "initial_state", kInitialStateNames, InitialState::prepared) ==
        InitialState::geostatic)
      out[setup.points.id[i]] = geostatic_target(job, setup, i);
  }
  return out;
}

std::string stress_text(const Mat3& s) {
  const Mat3 k = s / 1e3 + Mat3::Zero();  // + 0: no "-0" in the log
  return fmt::format("({:.4g}, {:.4g}, {:.4g}, {:.4g}, {:.4g}, {:.4g}) kPa", k(0, 0), k(1, 1),
                     k(2, 2), k(1, 2), k(0, 2), k(0, 1));
}

}  // namespace app
