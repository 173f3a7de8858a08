// Named-field state of a Simulation (flat arrays; vectors as 3N doubles, matrices row-major).
#include "dem/state.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/errors.hpp"
#include "common/state_params.hpp"
#include "common/tensor.hpp"

namespace dem {

using common::Mat3;
using common::Vec3;

namespace {

// The parameters are the rows of the parameter and choice tables (params.hpp), each a field
// named by its job key under params/material/ or params/numerics/ (common/state_params.hpp).
constexpr std::string_view kWhat = "dem state";

// Versions 2 to 4 wrote some parameters under their C++ member's name: the rows they are read
// into (docs/reference/checkpoint.md, version history).
constexpr common::FormerField kFormerMaterial[] = {
    {"young_modulus", "young"},        {"friction_angle", "friction_deg"},
    {"stiffness_ratio", "ks_over_kn"}, {"rolling_stiffness", "alpha_r"},
    {"rolling_strength", "eta_r"},     {"twisting.stiffness", "alpha_t"},
    {"twisting.strength", "eta_t"},
};
constexpr common::FormerField kFormerHertzMindlin[] = {
    {"poisson_ratio", "poisson"},
    {"rolling_stiffness", "krot"},
    {"rolling_strength", "eta"},
    {"twisting_stiffness", "ktwist"},
};
// dt_refresh: the standalone sample's interval before the RVEs' own dt_refresh took that name
// alone; skin_min_factor: absent before the adaptive skin (2026-11-26), a fixed skin.
constexpr common::FormerField kFormerNumerics[] = {
    {"timestep_safety", "dt_safety"},
    {"verlet_skin", "skin_factor"},
    {"verlet_skin_min", "skin_min_factor", true},
    {"timestep_update_interval", "timestep_update_interval"},
    {"timestep_update_interval", "dt_refresh"},
};
std::vector<double> flat(const std::vector<Vec3>& v) {
  std::vector<double> out(3 * v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (int a = 0; a < 3; ++a) out[3 * i + a] = v[i][a];
  }
  return out;
}
std::vector<double> flat(const Mat3& m) {
  std::vector<double> out(9);
  common::row_major_out(out.data()) = m;
  return out;
}

struct Reader {
  const common::StateReader& r;
  std::string prefix;
  std::vector<double> f64(const std::string& name, std::size_t n) const {
    auto v = r.read_f64(prefix + name);
    if (v.size() != n) {
      throw common::InputError("dem state: field '" + prefix + name + "' has " +
                               std::to_string(v.size()) + " values, expected " + std::to_string(n));
    }
    common::require_finite(v, "dem state: field '" + prefix + name + "'");
    return v;
  }
  /// A scalar f64 field, finite.
  double scalar(const std::string& name) const { return f64(name, 1)[0]; }
  /// A field of flags: every value 0 or 1.
  std::vector<std::int64_t> flags(const std::string& name, std::size_t n) const {
    auto v = i64(name, n);
    for (std::size_t k = 0; k < v.size(); ++k) {
      if (v[k] != 0 && v[k] != 1) {
        throw common::InputError("dem state: field '" + prefix + name + "' value " +
                                 std::to_string(k) + " is " + std::to_string(v[k]) +
                                 ": must be 0 or 1");
      }
    }
    return v;
  }
  std::vector<std::int64_t> i64(const std::string& name, std::size_t n) const {
    auto v = r.read_i64(prefix + name);
    if (v.size() != n) {
      throw common::InputError("dem state: field '" + prefix + name + "' has " +
                               std::to_string(v.size()) + " values, expected " + std::to_string(n));
    }
    return v;
  }
  std::vector<Vec3> vec3(const std::string& name, std::size_t n) const {
    const auto v = f64(name, 3 * n);
    std::vector<Vec3> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    return out;
  }
  Mat3 mat3(const std::string& name) const {
    const auto v = f64(name, 9);
    return common::row_major(v.data());
  }
};

}  // namespace

std::int64_t check_state_version(const common::StateReader& r, const std::string& pre) {
  const std::string name = pre + "dem/version";
  const std::int64_t version = common::read_scalar_i64(r, name);
  if (version >= kStateVersionOldest && version <= kStateVersion) return version;
  std::string why = "this build reads versions " + std::to_string(kStateVersionOldest) + " to " +
                    std::to_string(kStateVersion) + " only";
  if (version == 1) {
    why += " (version 1 stored the parameters as positional arrays such as 'params/material'; " +
           std::to_string(kStateVersion) +
           " stores named fields such as 'params/material/young_modulus')";
  }
  throw common::InputError("dem state: field '" + name + "' = " + std::to_string(version) + ": " +
                           why + "; restart from a state written by this version");
}

void save_simulation(const Simulation& sim, common::StateWriter& w, const std::string& pre) {
  const Spheres& s = sim.spheres();
  const Contacts& c = sim.contacts();
  const VerletState& vs = sim.verlet();
  const Material& mat = sim.law().material();
  const Numerics& num = sim.numerics();
  common::write_scalar(w, pre + "dem/version", kStateVersion);
  const std::string material = pre + "params/material/";
  common::write_params(w, material, kMaterial, mat);
  common::write_params(w, material, kCohFrict, mat);
  common::write_choices(w, material, kMaterialChoices, mat);
  for_each_table_law([&](const auto& d) {
    if (d.kind != mat.law) return;
    common::write_params(w, material + std::string(d.name()) + "/", d.table, mat.*d.params);
  });
  common::write_params(w, pre + "params/numerics/", kNumerics, num);
  w.write(pre + "cell/h", flat(sim.cell().h));
  w.write(pre + "cell/l", flat(sim.cell().l));
  w.write(pre + "spheres/x", flat(s.x));
  w.write(pre + "spheres/u", flat(s.u));
  w.write(pre + "spheres/w", flat(s.w));
  w.write(pre + "spheres/force", flat(s.force));
  w.write(pre + "spheres/torque", flat(s.torque));
  w.write(pre + "spheres/r", s.r);
  w.write(pre + "spheres/fixed", std::vector<std::int64_t>(s.fixed.begin(), s.fixed.end()));

  const std::size_t np = c.size();
  std::vector<std::int64_t> pair(2 * np);
  std::vector<std::int64_t> image(3 * np);
  std::vector<std::int64_t> active(np);
  std::vector<Vec3> normal(np);
  std::vector<Vec3> shear(np);
  std::vector<Vec3> roll(np);
  std::vector<Vec3> twist(np);
  for (std::size_t p = 0; p < np; ++p) {
    pair[2 * p] = c.i[p];
    pair[2 * p + 1] = c.j[p];
    for (int a = 0; a < 3; ++a) image[3 * p + a] = c.k[p][a];
    active[p] = c.active[p];
    const CohFrictHistory h = c.hist.get(p);
    normal[p] = h.normal;
    shear[p] = h.shear;
    roll[p] = h.roll;
    twist[p] = h.twist;
  }
  w.write(pre + "contacts/pair", pair);
  w.write(pre + "contacts/image", image);
  w.write(pre + "contacts/active", active);
  // The other properties follow from the radii and the material (version 2 stored them too).
  w.write(pre + "contacts/tan_phi", c.tan_phi);
  w.write(pre + "contacts/normal", flat(normal));
  w.write(pre + "contacts/shear_force", flat(shear));
  w.write(pre + "contacts/rolling_moment", flat(roll));
  w.write(pre + "contacts/twisting_moment", flat(twist));
  w.write(pre + "contacts/force", flat(c.force));
  w.write(pre + "contacts/torque_i", flat(c.torque_i));
  w.write(pre + "contacts/torque_j", flat(c.torque_j));
  w.write(pre + "contacts/branch", flat(c.branch));

  w.write(pre + "verlet/x_ref", flat(vs.x_ref));
  w.write(pre + "verlet/h_ref_inv", flat(vs.h_ref_inv));
  common::write_scalar(w, pre + "verlet/skin", vs.skin);
  common::write_scalar(w, pre + "verlet/r_max", vs.r_max);
  common::write_scalar(w, pre + "verlet/builds", vs.builds);
  common::write_scalar(w, pre + "verlet/built_at_step", vs.built_at_step);
  common::write_scalar(w, pre + "verlet/shell_pairs", vs.shell_pairs);
  common::write_scalar(w, pre + "verlet/pending", std::int64_t{sim.neighbors_pending() ? 1 : 0});

  common::write_scalar(w, pre + "counters/time", sim.time());
  common::write_scalar(w, pre + "counters/dt", sim.dt());
  common::write_scalar(w, pre + "counters/steps", sim.steps());
  w.write(pre + "stress", flat(sim.stress()));
}

namespace {

// The material (contact law and its parameters) of a state of `version`.
Material read_material(const common::StateReader& r, const std::string& pre, std::int64_t version) {
  Material mat;
  const std::string dir = pre + "params/material/";
  const bool former = version < kStateVersion;
  const std::span<const common::FormerField> renamed =
      former ? std::span<const common::FormerField>(kFormerMaterial)
             : std::span<const common::FormerField>();
  common::read_params(r, dir, kMaterial, mat, kWhat, renamed);
  common::read_params(r, dir, kCohFrict, mat, kWhat, renamed);
  if (!former) {
    common::read_choices(r, dir, kMaterialChoices, mat, kWhat);
  } else if (version == kStateVersionOtherLaw) {
    // Version 4 stored the law's enumerator: a law of its own table (every law but CohFrict).
    const std::string name = dir + "contact_law";
    const std::int64_t law = common::read_scalar_i64(r, name);
    bool known = false;
    std::string laws;
    for_each_table_law([&](const auto& d) {
      laws += (laws.empty() ? "" : ", ") + std::to_string(static_cast<int>(d.kind)) + " (" +
              std::string(d.name()) + ")";
      if (law != static_cast<std::int64_t>(d.kind)) return;
      known = true;
      mat.law = d.kind;
    });
    if (!known) {
      throw common::InputError("dem state: field '" + name + "' = " + std::to_string(law) +
                               ": must be one of " + laws + " in a version " +
                               std::to_string(kStateVersionOtherLaw) + " state");
    }
  }  // versions 2 and 3: CohFrict
  for_each_table_law([&](const auto& d) {
    if (d.kind != mat.law) return;
    // Version 4 knew Hertz-Mindlin only, under its C++ members' names.
    const bool hm = former && d.kind == ContactLawKind::hertz_mindlin;
    common::read_params(r, dir + std::string(d.name()) + "/", d.table, mat.*d.params, kWhat,
                        hm ? std::span<const common::FormerField>(kFormerHertzMindlin)
                           : std::span<const common::FormerField>());
  });
  return mat;
}

Numerics read_numerics(const common::StateReader& r, const std::string& pre, std::int64_t version) {
  Numerics num;
  if (version < kStateVersion) {
    num.skin_min_factor = 0.0;  // a state of before the adaptive skin: a fixed skin
    common::read_params(r, pre + "params/numerics/", kNumerics, num, kWhat, kFormerNumerics);
  } else {
    common::read_params(r, pre + "params/numerics/", kNumerics, num, kWhat);
  }
  return num;
}

Spheres read_spheres(const common::StateReader& r, const Reader& rd, const std::string& pre,
                     double density) {
  const auto radii = r.read_f64(pre + "spheres/r");
  const std::size_t n = radii.size();
  Spheres s;
  for (double ri : radii) s.add(Vec3::Zero(), ri, density);
  s.x = rd.vec3("spheres/x", n);
  s.u = rd.vec3("spheres/u", n);
  s.w = rd.vec3("spheres/w", n);
  s.force = rd.vec3("spheres/force", n);
  s.torque = rd.vec3("spheres/torque", n);
  const auto fixed = rd.flags("spheres/fixed", n);
  for (std::size_t i = 0; i < n; ++i) s.fixed[i] = static_cast<std::uint8_t>(fixed[i]);
  return s;
}

// The contact list (pairs i < j < n, their images, history and forces).
void read_contacts(const common::StateReader& r, const Reader& rd, const std::string& pre,
                   Simulation& sim) {
  const std::size_t n = sim.spheres().size();
  const std::size_t np = r.read_i64(pre + "contacts/active").size();
  const auto active = rd.flags("contacts/active", np);
  const auto pair = rd.i64("contacts/pair", 2 * np);
  const auto image = rd.i64("contacts/image", 3 * np);
  // Version 2 also stored kn, ks, kr, kt, roll_cap and twist_cap per pair: functions of the radii
  // and the material, computed again (the same bits), not read.
  const auto tan_phi = rd.f64("contacts/tan_phi", np);
  const auto normal = rd.vec3("contacts/normal", np);
  const auto shear = rd.vec3("contacts/shear_force", np);
  const auto roll = rd.vec3("contacts/rolling_moment", np);
  const auto twist = rd.vec3("contacts/twisting_moment", np);
  Contacts& c = sim.contacts();
  c.resize(np);
  for (std::size_t p = 0; p < np; ++p) {
    c.i[p] = static_cast<std::int32_t>(pair[2 * p]);
    c.j[p] = static_cast<std::int32_t>(pair[2 * p + 1]);
    // i < j (as the neighbour search builds them): a pair of a sphere with itself would touch
    // along no normal. Checked on the stored values, before any narrowing.
    if (pair[2 * p] < 0 || pair[2 * p] >= pair[2 * p + 1] ||
        static_cast<std::uint64_t>(pair[2 * p + 1]) >= n) {
      throw common::InputError("dem state: field '" + pre + "contacts/pair' pair " +
                               std::to_string(p) + " = (" + std::to_string(pair[2 * p]) + ", " +
                               std::to_string(pair[2 * p + 1]) + "): must be spheres i < j < " +
                               std::to_string(n));
    }
    c.k[p] = common::Vec3i(static_cast<int>(image[3 * p]), static_cast<int>(image[3 * p + 1]),
                           static_cast<int>(image[3 * p + 2]));
    c.active[p] = static_cast<std::uint8_t>(active[p]);
    c.tan_phi[p] = tan_phi[p];
    c.hist.set(p, CohFrictHistory{normal[p], shear[p], roll[p], twist[p]});
  }
  c.force = rd.vec3("contacts/force", np);
  c.torque_i = rd.vec3("contacts/torque_i", np);
  c.torque_j = rd.vec3("contacts/torque_j", np);
  c.branch = rd.vec3("contacts/branch", np);
  c.build_sphere_lists(n);
}

// The Verlet list's state and the counters (time, steps, dt), checked against each other.
void read_verlet_and_counters(const common::StateReader& r, const Reader& rd,
                              const std::string& pre, Simulation& sim) {
  const std::size_t n = sim.spheres().size();
  const std::size_t np = sim.contacts().size();
  VerletState& vs = sim.verlet();
  vs.x_ref = rd.vec3("verlet/x_ref", r.read_f64(pre + "verlet/x_ref").size() / 3);
  vs.h_ref_inv = rd.mat3("verlet/h_ref_inv");
  vs.skin = rd.scalar("verlet/skin");
  vs.r_max = rd.scalar("verlet/r_max");
  vs.builds = common::read_scalar_i64(r, pre + "verlet/builds");
  sim.set_neighbors_pending(rd.flags("verlet/pending", 1)[0] != 0);
  // The list's guarantee rests on these: a skin of zero or less, or an r_max below the largest
  // radius, would let contacts form unseen. The list (x_ref) is that of all spheres or none.
  const auto& radii = sim.spheres().r;
  const double r_largest = n > 0 ? *std::max_element(radii.begin(), radii.end()) : 0.0;
  if (!(vs.skin > 0.0) || vs.r_max < r_largest || vs.builds < 0 ||
      (!vs.x_ref.empty() && vs.x_ref.size() != n)) {
    throw common::InputError(
        "dem state: fields '" + pre + "verlet/*': skin " + std::to_string(vs.skin) + " m, r_max " +
        std::to_string(vs.r_max) + " m, builds " + std::to_string(vs.builds) + ", x_ref of " +
        std::to_string(vs.x_ref.size()) + " spheres: the skin must be > 0, r_max " +
        ">= the largest radius (" + std::to_string(r_largest) + " m), builds >= 0 and x_ref of " +
        "0 or " + std::to_string(n) + " spheres");
  }

  const double time = rd.scalar("counters/time");
  const std::int64_t steps = common::read_scalar_i64(r, pre + "counters/steps");
  const double dt = rd.scalar("counters/dt");
  if (steps < 0 || dt < 0.0) {
    throw common::InputError("dem state: fields '" + pre +
                             "counters/steps' = " + std::to_string(steps) + ", '" + pre +
                             "counters/dt' = " + std::to_string(dt) + ": must be >= 0");
  }
  // The adaptive skin's inputs (written since it came, 2026-11-26): absent, the list counts as
  // built at this step with no pair to spare (its skin then changes at its next due rebuild).
  vs.built_at_step = r.has(pre + "verlet/built_at_step")
                         ? common::read_scalar_i64(r, pre + "verlet/built_at_step")
                         : steps;
  vs.shell_pairs = r.has(pre + "verlet/shell_pairs")
                       ? common::read_scalar_i64(r, pre + "verlet/shell_pairs")
                       : 0;
  if (vs.built_at_step < 0 || vs.built_at_step > steps || vs.shell_pairs < 0 ||
      vs.shell_pairs > static_cast<std::int64_t>(np)) {
    throw common::InputError(
        "dem state: fields '" + pre +
        "verlet/built_at_step' = " + std::to_string(vs.built_at_step) + ", '" + pre +
        "verlet/shell_pairs' = " + std::to_string(vs.shell_pairs) +
        ": the step of the last build must be in [0, " + std::to_string(steps) +
        "] (counters/steps) and the shell pairs in [0, " + std::to_string(np) + "] (the pairs)");
  }
  sim.set_counters(time, steps);
  sim.set_dt(dt);
}

}  // namespace

Simulation load_simulation(const common::StateReader& r, const std::string& pre) {
  const Reader rd{r, pre};
  const std::int64_t version = check_state_version(r, pre);
  const Material mat = read_material(r, pre, version);
  const Numerics num = read_numerics(r, pre, version);
  Spheres s = read_spheres(r, rd, pre, mat.density);
  PeriodicCell cell;
  cell.h = rd.mat3("cell/h");
  cell.l = rd.mat3("cell/l");
  Simulation sim(std::move(s), cell, mat, num);
  read_contacts(r, rd, pre, sim);
  read_verlet_and_counters(r, rd, pre, sim);
  sim.set_stress(rd.mat3("stress"));
  return sim;
}

}  // namespace dem
