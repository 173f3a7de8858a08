// Coulomb friction of a rigid wall on one node (see header).
#include "mpm/friction.hpp"

#include <algorithm>
#include <cmath>

namespace mpm {

WallCorrection apply_wall_friction(const common::Vec3& v_trial, const common::Vec3& v_wall,
                                   const WallFriction& wall) {
  common::Vec3 n = common::Vec3::Zero();
  n[wall.axis] = -static_cast<double>(wall.side);
  const common::Vec3 v_rel = v_trial - v_wall;
  const double v_n = v_rel.dot(n);
  if (wall.contact == WallContact::no_penetration && !(v_n < 0.0)) return {v_trial, false};
  const double dv_n = -v_n;
  common::Vec3 v_t = v_rel - v_n * n;
  const double slip = v_t.norm();
  if (slip > 0.0) {
    const double reduce = std::min(slip, wall.mu * std::max(dv_n, 0.0));
    v_t *= (slip - reduce) / slip;
  }
  return {common::Vec3(v_wall + v_t), true};
}

}  // namespace mpm
