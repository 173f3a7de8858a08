// Measurements over spheres and contacts in fixed (serial) order.
#include "dem/measures.hpp"

#include <cmath>
#include <numbers>
#include <vector>

namespace dem {

using common::Mat3;
using common::Vec3;

double void_ratio(const Simulation& sim) {
  double vs = 0.0;
  for (double r : sim.spheres().r) vs += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return sim.cell().volume() / vs - 1.0;
}

Measures measure(const Simulation& sim) {
  Measures m;
  const Spheres& s = sim.spheres();
  const Contacts& c = sim.contacts();
  m.stress = sim.stress();
  m.p = pressure(m.stress);
  m.q = deviatoric(m.stress);
  m.void_ratio = void_ratio(sim);

  const std::size_t n = s.size();
  std::vector<int> deg(n, 0);
  double sum_fc = 0.0;
  for (std::size_t p = 0; p < c.size(); ++p) {
    if (!c.active[p]) continue;
    ++m.n_contacts;
    ++deg[c.i[p]];
    ++deg[c.j[p]];
    const Vec3 nn = at(c.hist.normal, p);
    m.fabric += nn * nn.transpose();
    sum_fc += c.force[p].norm();
  }
  if (m.n_contacts > 0) m.fabric /= static_cast<double>(m.n_contacts);
  m.z = n > 0 ? 2.0 * static_cast<double>(m.n_contacts) / static_cast<double>(n) : 0.0;

  // Rattlers: remove spheres with fewer than 2 contacts, repeatedly.
  std::vector<char> rattler(n, 0);
  const bool lists = c.sphere_offset.size() == n + 1;
  std::vector<int> d2 = deg;
  for (bool changed = lists; changed;) {
    changed = false;
    for (std::size_t q = 0; q < n; ++q) {
      if (!rattler[q] && d2[q] < 2) {
        rattler[q] = 1;
        changed = true;
        for (std::int64_t e = c.sphere_offset[q]; e < c.sphere_offset[q + 1]; ++e) {
          const std::int64_t p0 = c.sphere_pairs[e];
          const std::size_t p = static_cast<std::size_t>(p0 >= 0 ? p0 : -p0 - 1);
          if (!c.active[p]) continue;
          const std::size_t other = static_cast<std::size_t>(p0 >= 0 ? c.j[p] : c.i[p]);
          if (!rattler[other]) --d2[other];
        }
      }
    }
  }
  std::int64_t nm = 0;
  std::int64_t cm = 0;
  for (std::size_t q = 0; q < n; ++q) nm += rattler[q] ? 0 : 1;
  for (std::size_t p = 0; p < c.size(); ++p) {
    if (c.active[p] && !rattler[c.i[p]] && !rattler[c.j[p]]) ++cm;
  }
  m.z_mech = nm > 0 ? 2.0 * static_cast<double>(cm) / static_cast<double>(nm) : 0.0;

  double sum_fs = 0.0;
  for (std::size_t q = 0; q < n; ++q) {
    if (s.fixed[q]) continue;
    sum_fs += s.force[q].norm();
    m.kinetic += 0.5 * (s.m[q] * s.u[q].squaredNorm() + s.inertia[q] * s.w[q].squaredNorm());
  }
  m.unbalanced =
      (m.n_contacts > 0 && sum_fc > 0.0)
          ? (sum_fs / static_cast<double>(n)) / (sum_fc / static_cast<double>(m.n_contacts))
          : 0.0;
  return m;
}

}  // namespace dem
