// Job -> mpm configuration: see mpm_setup.hpp.
#include "app/setup/mpm_setup.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "app/job/schema_params.hpp"
#include "common/errors.hpp"
#include "mpm/solver_choices.hpp"

namespace app {

namespace {
common::Vec3 vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

common::Mat3 voigt_stress(const std::vector<double>& s) {  // xx, yy, zz, yz, xz, xy
  common::Mat3 m;
  m << s[0], s[5], s[4], s[5], s[1], s[3], s[4], s[3], s[2];
  return m;
}

common::Vec3i points_per_cell(const Job& job, const std::string& key) {
  const auto n = job.per_axis(key);
  return {static_cast<int>(n[0]), static_cast<int>(n[1]), static_cast<int>(n[2])};
}

/// The frictional wall, time window and name keys of one [[mpm.velocity]] (`base` ends in '.').
void velocity_extras(const Job& job, const std::string& base, mpm::VelocityConstraint& c) {
  const bool face = job.has(base + "face");
  if (job.has(base + "normal") && !job.has(base + "friction")) {
    throw common::InputError(
        job.message(base + "normal", "only used with friction (a frictional wall's side)"));
  }
  if (job.has(base + "contact") && !job.has(base + "friction")) {
    throw common::InputError(job.message(
        base + "contact", "only used with friction (give friction = 0 for a smooth wall)"));
  }
  if (job.has(base + "friction")) {
    if (face && job.has(base + "normal")) {
      throw common::InputError(
          job.message(base + "normal", "not used with face: the face is the wall's side"));
    }
    if (!face && !job.has(base + "normal")) {
      throw common::InputError(
          job.message(base + "friction",
                      "a frictional box or node needs normal (the side of the material "
                      "the wall lies on, e.g. normal = \"z+\" for a top platen)"));
    }
    const mpm::Face side_face = choice_of(job, base + (face ? "face" : "normal"), mpm::kFaceNames);
    const int axis = mpm::axis_of(side_face);
    const std::string n_key = base + std::string(1, static_cast<char>('x' + axis));
    if (!job.has(n_key)) {
      throw common::InputError(
          job.message(base + "friction",
                      fmt::format("a frictional wall needs its normal velocity {} (e.g. {} = 0.0)",
                                  n_key, static_cast<char>('x' + axis))));
    }
    c.wall = {axis, mpm::side_of(side_face), job.number(base + "friction"),
              choice_of(job, base + "contact", mpm::kWallContactNames, mpm::WallContact::fixed)};
  }
  if (job.has(base + "from")) c.from = job.number(base + "from");
  if (job.has(base + "until")) c.until = job.number(base + "until");
  if (job.has(base + "from") && job.has(base + "until") && !(c.until > c.from)) {
    throw common::InputError(job.message(base + "until", "must be after from"));
  }
  if (job.has(base + "name")) {
    const std::string& name = job.text(base + "name");
    const bool ok = !name.empty() && std::all_of(name.begin(), name.end(), [](char ch) {
      return std::isalnum(static_cast<unsigned char>(ch)) != 0 || ch == '_' || ch == '-';
    });
    if (!ok) {
      throw common::InputError(
          job.message(base + "name", "must be letters, digits, _ or - (a CSV column name)"));
    }
  }
}

// The rules between the transfer's knobs (flip, pic_time, xpic_order against the transfer), on
// the keys the job sets itself, not their defaults.
void transfer_rules(const Job& job, const mpm::SolverConfig& cfg) {
  auto given = [&job](const char* key) {
    const auto it = job.entries().find(key);
    return it != job.entries().end() && !it->second.defaulted;
  };
  const bool apic = cfg.transfer == mpm::Transfer::apic;
  if (apic && given("mpm.flip")) {
    throw common::InputError(
        job.message("mpm.flip",
                    "does not apply with mpm.transfer = \"apic\" (APIC's point velocity is the "
                    "grid's, PIC, with the affine part carried by C_p): remove one of the two"));
  }
  // The PIC share is set per step (flip < 1) or in time (pic_time > 0), not both; APIC has none.
  const bool per_step = given("mpm.flip") && job.number("mpm.flip") != 1.0;
  const bool in_time = given("mpm.pic_time") && job.number("mpm.pic_time") > 0.0;
  if (in_time && apic) {
    throw common::InputError(
        job.message("mpm.pic_time",
                    "does not apply with mpm.transfer = \"apic\" (it relaxes the FLIP part "
                    "of the FLIP/PIC blend towards PIC; APIC has no FLIP part)"));
  }
  if (in_time && per_step) {
    throw common::InputError(
        job.message("mpm.pic_time",
                    "with mpm.flip < 1: the PIC share is set either per step (mpm.flip) or "
                    "in time (mpm.pic_time, with flip = 1), not both: remove one of the two"));
  }
  // XPIC shapes the PIC share: it needs one, and APIC has none.
  if (given("mpm.xpic_order") && job.integer("mpm.xpic_order") > 1) {
    if (apic) {
      throw common::InputError(
          job.message("mpm.xpic_order",
                      "does not apply with mpm.transfer = \"apic\" (XPIC shapes the PIC share "
                      "of the FLIP/PIC update; APIC has its own): remove one of the two"));
    }
    if (!per_step && !in_time) {
      throw common::InputError(
          job.message("mpm.xpic_order",
                      "needs a PIC share to shape: with mpm.flip = 1 and no mpm.pic_time the "
                      "update is pure FLIP; set mpm.flip = 0 (XPIC alone), mpm.flip < 1 or "
                      "mpm.pic_time > 0 (a blend with FLIP)"));
    }
  }
}

// The material points of every mpm.body, with their materials and initial stresses.
void add_bodies(const Job& job, MpmSetup& setup) {
  const auto& grid = setup.config.grid;
  for (std::size_t b = 0; b < job.count("mpm.body"); ++b) {
    const std::string base = fmt::format("mpm.body[{}].", b);
    const std::int32_t material = choice_of(job, base + "material", kBodyMaterialNames);
    const bool is_dem = material == kDemMaterial;
    const std::size_t first = setup.points.size();
    std::size_t added = 0;
    try {
      added = mpm::fill_box(
          setup.points, grid, vec3(job.numbers(base + "min")), vec3(job.numbers(base + "max")),
          points_per_cell(job, base + "points_per_cell"), job.number(base + "density"), material);
    } catch (const common::InputError& e) {
      throw common::InputError(job.message(base + "max", e.what()));  // name the file, line and key
    }
    if (added == 0) {
      throw common::InputError(
          job.message(base + "max", "the box holds no material point (it covers no whole cell)"));
    }
    setup.body.resize(setup.points.size(), static_cast<std::int32_t>(b));
    if (job.has(base + "initial_stress")) {
      const common::Mat3 s0 = voigt_stress(job.numbers(base + "initial_stress"));
      for (std::size_t p = first; p < setup.points.size(); ++p) setup.points.stress[p] = s0;
      if (!is_dem) setup.elastic_initial_stress = s0;
    }
    setup.has_dem = setup.has_dem || is_dem;
    setup.has_elastic = setup.has_elastic || !is_dem;
  }
}

// The velocity constraint of the entry `base` (mpm.velocity[i].) on the grid: a face, a node or a
// box.
mpm::VelocityConstraint velocity_constraint(const Job& job, const std::string& base,
                                            const mpm::Grid& grid) {
  std::array<bool, 3> fixed{};
  common::Vec3 v = common::Vec3::Zero();
  for (int a = 0; a < 3; ++a) {
    const std::string key = base + std::string(1, static_cast<char>('x' + a));
    if (job.has(key)) {
      fixed[static_cast<std::size_t>(a)] = true;
      v[a] = job.number(key);
    }
  }
  mpm::VelocityConstraint c;
  if (job.has(base + "face")) {
    const mpm::Face face = choice_of(job, base + "face", mpm::kFaceNames);
    c = mpm::face_constraint(grid, mpm::axis_of(face), mpm::side_of(face), fixed, v);
  } else if (job.has(base + "node")) {
    c = mpm::node_constraint(grid, vec3(job.numbers(base + "node")), fixed, v);
  } else {
    c.lo = vec3(job.numbers(base + "min"));
    c.hi = vec3(job.numbers(base + "max"));
    c.fixed = fixed;
    c.velocity = v;
  }
  return c;
}

// mpm.velocity[i]'s name differs from the earlier constraints' (written or default names).
void unique_name(const Job& job, std::size_t i, const std::vector<mpm::VelocityConstraint>& earlier,
                 const std::string& name) {
  const std::string base = fmt::format("mpm.velocity[{}].", i);
  for (std::size_t k = 0; k < earlier.size(); ++k) {
    if (earlier[k].name != name) continue;
    // Name the key that was written: this entry's name, or the earlier one's that took the
    // default name of this entry (velocity_<i>).
    const std::string other = fmt::format("mpm.velocity[{}]", k);
    const std::string here = fmt::format("mpm.velocity[{}]", i);
    throw common::InputError(
        job.has(base + "name")
            ? job.message(base + "name",
                          fmt::format("{} is already named so{}: names are unique", other,
                                      job.has(other + ".name") ? "" : " (its default name)"))
            : job.message(other + ".name",
                          fmt::format("the default name of {}: names are unique (name {} "
                                      "too, or rename this one)",
                                      here, here)));
  }
}

}  // namespace

MpmSetup mpm_setup(const Job& job) {
  MpmSetup setup;
  auto& cfg = setup.config;
  cfg.grid.origin = vec3(job.numbers("mpm.grid.origin"));
  cfg.grid.spacing = vec3(job.numbers("mpm.grid.spacing"));
  const auto& cells = job.integers("mpm.grid.cells");
  cfg.grid.cells = common::Vec3i(static_cast<int>(cells[0]), static_cast<int>(cells[1]),
                                 static_cast<int>(cells[2]));
  fill_choices_from_job(job, mpm::kSolverChoices, cfg);  // shape, ..., move_points, plane_strain
  transfer_rules(job, cfg);
  if (job.has("mpm.gravity")) cfg.gravity = vec3(job.numbers("mpm.gravity"));
  fill_from_job(job, mpm::kSolverConfig, cfg);  // flip, damping, dt, cfl, mass_threshold, ...
  setup.end_time = job.number("mpm.end_time");

  add_bodies(job, setup);

  for (std::size_t i = 0; i < job.count("mpm.velocity"); ++i) {
    const std::string base = fmt::format("mpm.velocity[{}].", i);
    mpm::VelocityConstraint c = velocity_constraint(job, base, cfg.grid);
    velocity_extras(job, base, c);
    c.name = job.has(base + "name") ? job.text(base + "name") : fmt::format("velocity_{}", i);
    unique_name(job, i, setup.constraints, c.name);
    setup.constraints.push_back(std::move(c));
  }
  for (std::size_t i = 0; i < job.count("mpm.traction"); ++i) {
    const std::string base = fmt::format("mpm.traction[{}].", i);
    mpm::TractionLoad load;
    const mpm::Face face = choice_of(job, base + "face", mpm::kFaceNames);
    load.axis = mpm::axis_of(face);
    load.side = mpm::side_of(face);
    load.pressure = job.number(base + "pressure");
    setup.tractions.push_back(load);
  }
  return setup;
}

}  // namespace app
