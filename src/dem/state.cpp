// Named-field state of a Simulation (flat arrays; vectors as 3N doubles, matrices row-major).
#include "dem/state.hpp"

#include <vector>

#include "common/errors.hpp"

namespace dem {

using common::Mat3;
using common::Vec3;

namespace {

constexpr std::int64_t kVersion = 1;

std::vector<double> flat(const std::vector<Vec3>& v) {
  std::vector<double> out(3 * v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (int a = 0; a < 3; ++a) out[3 * i + a] = v[i][a];
  }
  return out;
}
std::vector<double> flat(const Mat3& m) {
  std::vector<double> out(9);
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) out[3 * a + b] = m(a, b);
  }
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
    Mat3 m;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) m(a, b) = v[3 * a + b];
    }
    return m;
  }
};

}  // namespace

void save_simulation(const Simulation& sim, common::StateWriter& w, const std::string& pre) {
  const Spheres& s = sim.spheres();
  const Contacts& c = sim.contacts();
  const VerletState& vs = sim.verlet();
  const Material& mat = sim.law().material();
  const Numerics& num = sim.numerics();
  const std::vector<std::int64_t> version{kVersion};
  w.write(pre + "dem/version", version);
  const std::vector<double> pm{mat.density, mat.young, mat.ks_over_kn, mat.friction_deg,
                               mat.alpha_r, mat.eta_r, mat.alpha_t,    mat.eta_t};
  w.write(pre + "params/material", pm);
  const std::vector<double> pn{num.damping, num.dt_safety, num.skin_factor,
                               static_cast<double>(num.dt_refresh), num.max_skew};
  w.write(pre + "params/numerics", pn);
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
  std::vector<double> props(7 * np);
  std::vector<Vec3> normal(np);
  std::vector<Vec3> shear(np);
  std::vector<Vec3> roll(np);
  std::vector<Vec3> twist(np);
  for (std::size_t p = 0; p < np; ++p) {
    pair[2 * p] = c.i[p];
    pair[2 * p + 1] = c.j[p];
    for (int a = 0; a < 3; ++a) image[3 * p + a] = c.k[p][a];
    active[p] = c.active[p];
    const CohFrictProps& q = c.props[p];
    const double pv[7] = {q.kn, q.ks, q.kr, q.kt, q.tan_phi, q.roll_cap, q.twist_cap};
    for (int a = 0; a < 7; ++a) props[7 * p + a] = pv[a];
    normal[p] = c.hist[p].normal;
    shear[p] = c.hist[p].shear;
    roll[p] = c.hist[p].roll;
    twist[p] = c.hist[p].twist;
  }
  w.write(pre + "contacts/pair", pair);
  w.write(pre + "contacts/image", image);
  w.write(pre + "contacts/active", active);
  w.write(pre + "contacts/props", props);
  w.write(pre + "contacts/normal", flat(normal));
  w.write(pre + "contacts/shear_force", flat(shear));
  w.write(pre + "contacts/rolling_moment", flat(roll));
  w.write(pre + "contacts/twisting_moment", flat(twist));
  w.write(pre + "contacts/force", flat(c.force));
  w.write(pre + "contacts/torque_i", flat(c.torque_i));
  w.write(pre + "contacts/torque_j", flat(c.torque_j));
  w.write(pre + "contacts/branch", flat(c.branch));
  w.write(pre + "contacts/normal_force", c.fn);

  w.write(pre + "verlet/x_ref", flat(vs.x_ref));
  w.write(pre + "verlet/h_ref_inv", flat(vs.h_ref_inv));
  const std::vector<double> vsd{vs.skin, vs.r_max};
  w.write(pre + "verlet/skin_rmax", vsd);
  const std::vector<std::int64_t> vsi{vs.builds, sim.neighbors_pending() ? 1 : 0};
  w.write(pre + "verlet/builds_pending", vsi);

  const std::vector<double> cd{sim.time(), sim.dt()};
  w.write(pre + "counters/time_dt", cd);
  const std::vector<std::int64_t> ci{sim.steps()};
  w.write(pre + "counters/steps", ci);
  w.write(pre + "stress", flat(sim.stress()));
}

Simulation load_simulation(const common::StateReader& r, const std::string& pre) {
  const Reader rd{r, pre};
  if (rd.i64("dem/version", 1)[0] != kVersion) {
    throw common::InputError("dem state: field '" + pre + "dem/version' is not " +
                             std::to_string(kVersion));
  }
  const auto pm = rd.f64("params/material", 8);
  const Material mat{pm[0], pm[1], pm[2], pm[3], pm[4], pm[5], pm[6], pm[7]};
  const auto pn = rd.f64("params/numerics", 5);
  Numerics num;
  num.damping = pn[0];
  num.dt_safety = pn[1];
  num.skin_factor = pn[2];
  num.dt_refresh = static_cast<std::int64_t>(pn[3]);
  num.max_skew = pn[4];

  const auto radii = r.read_f64(pre + "spheres/r");
  const std::size_t n = radii.size();
  Spheres s;
  for (double ri : radii) s.add(Vec3::Zero(), ri, mat.density);
  s.x = rd.vec3("spheres/x", n);
  s.u = rd.vec3("spheres/u", n);
  s.w = rd.vec3("spheres/w", n);
  s.force = rd.vec3("spheres/force", n);
  s.torque = rd.vec3("spheres/torque", n);
  const auto fixed = rd.i64("spheres/fixed", n);
  for (std::size_t i = 0; i < n; ++i) s.fixed[i] = static_cast<std::uint8_t>(fixed[i]);
  PeriodicCell cell;
  cell.h = rd.mat3("cell/h");
  cell.l = rd.mat3("cell/l");
  Simulation sim(std::move(s), cell, mat, num);

  const auto active = r.read_i64(pre + "contacts/active");
  const std::size_t np = active.size();
  const auto pair = rd.i64("contacts/pair", 2 * np);
  const auto image = rd.i64("contacts/image", 3 * np);
  const auto props = rd.f64("contacts/props", 7 * np);
  const auto normal = rd.vec3("contacts/normal", np);
  const auto shear = rd.vec3("contacts/shear_force", np);
  const auto roll = rd.vec3("contacts/rolling_moment", np);
  const auto twist = rd.vec3("contacts/twisting_moment", np);
  Contacts& c = sim.contacts();
  c.resize(np);
  for (std::size_t p = 0; p < np; ++p) {
    c.i[p] = static_cast<std::int32_t>(pair[2 * p]);
    c.j[p] = static_cast<std::int32_t>(pair[2 * p + 1]);
    if (c.i[p] < 0 || c.j[p] < 0 || static_cast<std::size_t>(c.i[p]) >= n ||
        static_cast<std::size_t>(c.j[p]) >= n) {
      throw common::InputError("dem state: field '" + pre +
                               "contacts/pair' names a sphere out of range");
    }
    c.k[p] = common::Vec3i(static_cast<int>(image[3 * p]), static_cast<int>(image[3 * p + 1]),
                           static_cast<int>(image[3 * p + 2]));
    c.active[p] = static_cast<std::uint8_t>(active[p]);
    c.props[p] =
        CohFrictProps{props[7 * p],     props[7 * p + 1], props[7 * p + 2], props[7 * p + 3],
                      props[7 * p + 4], props[7 * p + 5], props[7 * p + 6]};
    c.hist[p] = CohFrictHistory{normal[p], shear[p], roll[p], twist[p]};
  }
  c.force = rd.vec3("contacts/force", np);
  c.torque_i = rd.vec3("contacts/torque_i", np);
  c.torque_j = rd.vec3("contacts/torque_j", np);
  c.branch = rd.vec3("contacts/branch", np);
  c.fn = rd.f64("contacts/normal_force", np);
  c.build_sphere_lists(n);

  VerletState& vs = sim.verlet();
  vs.x_ref = rd.vec3("verlet/x_ref", r.read_f64(pre + "verlet/x_ref").size() / 3);
  vs.h_ref_inv = rd.mat3("verlet/h_ref_inv");
  const auto vsd = rd.f64("verlet/skin_rmax", 2);
  vs.skin = vsd[0];
  vs.r_max = vsd[1];
  const auto vsi = rd.i64("verlet/builds_pending", 2);
  vs.builds = vsi[0];
  sim.set_neighbors_pending(vsi[1] != 0);

  const auto cd = rd.f64("counters/time_dt", 2);
  sim.set_counters(cd[0], rd.i64("counters/steps", 1)[0]);
  sim.set_dt(cd[1]);
  sim.set_stress(rd.mat3("stress"));
  return sim;
}

}  // namespace dem
