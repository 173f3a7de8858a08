// Free flight of a periodic cell without contacts (see free_flight.hpp).
#include "dem/free_flight.hpp"

#include <algorithm>
#include <cstddef>

#include "dem/neighbor_search.hpp"

namespace dem {

using common::Mat3;
using common::Vec3;

namespace {
// The closest approach of d(t) = d0 + t v on [0, dt], squared.
double closest2(const Vec3& d0, const Vec3& v, double dt) {
  const double vv = v.squaredNorm();
  double t = 0.0;
  if (vv > 0.0) t = std::clamp(-d0.dot(v) / vv, 0.0, dt);
  return (d0 + t * v).squaredNorm();
}
}  // namespace

bool free_flight_holds(const Simulation& sim, double dt, const Mat3& l, double margin) {
  const Spheres& s = sim.spheres();
  const Contacts& c = sim.contacts();
  const VerletState& vs = sim.verlet();
  if (sim.neighbors_pending() || vs.x_ref.size() != s.size()) return false;
  for (const auto a : c.active) {
    if (a != 0) return false;
  }
  const Mat3& h = sim.cell().h;
  for (std::size_t p = 0; p < c.size(); ++p) {
    const auto i = static_cast<std::size_t>(c.i[p]);
    const auto j = static_cast<std::size_t>(c.j[p]);
    const Vec3 d0 = s.x[j] + h * c.k[p].cast<double>() - s.x[i];
    const Vec3 v = (s.u[j] - s.u[i]) + l * d0;
    const double reach = (s.r[i] + s.r[j]) * (1.0 + margin);
    if (!(closest2(d0, v, dt) > reach * reach)) return false;
  }
  // The list's measure at both ends of the step (at its start the last neighbour check kept the
  // list, so it is below the skin unless the spheres were moved since).
  const Mat3 h_end = h + (dt * l) * h;
  const Mat3 f0 = h * vs.h_ref_inv;
  const Mat3 f1 = h_end * vs.h_ref_inv;
  const double a0 = max_drift2(s, f0, vs);
  double a1 = 0.0;
  for (std::size_t q = 0; q < s.size(); ++q) {
    const Vec3 x_end = s.x[q] + dt * (s.u[q] + l * s.x[q]);
    if (!x_end.allFinite()) return false;  // (a NaN would drop out of the maximum)
    a1 = std::max(a1, (x_end - f1 * vs.x_ref[q]).squaredNorm());
  }
  return rebuild_measure(a0, f0, vs.r_max, vs.skin) < vs.skin &&
         rebuild_measure(a1, f1, vs.r_max, vs.skin) < vs.skin;
}

}  // namespace dem
