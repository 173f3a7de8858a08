// Grid solve: nodal velocity and damped acceleration (eq. 8).
#include "mpm/grid_solve.hpp"

#include <cmath>

#include "mpm/parallel.hpp"

namespace mpm {

double typical_nodal_mass(const GridFields& fields) {
  if (fields.active.empty()) return 0.0;
  double total = 0.0;
  for (const std::int64_t i : fields.active) total += fields.mass[static_cast<std::size_t>(i)];
  return total / static_cast<double>(fields.active.size());
}

void compute_nodal_velocity(double threshold, GridFields& fields) {
  const auto n = static_cast<std::int64_t>(fields.active.size());
  for_each_index(n, [&](std::int64_t q) {
    const auto i = static_cast<std::size_t>(fields.active[static_cast<std::size_t>(q)]);
    const double m_i = fields.mass[i];
    fields.velocity[i] = (m_i >= threshold && m_i > 0.0) ? common::Vec3(fields.momentum[i] / m_i)
                                                         : common::Vec3::Zero();
  });
}

void compute_nodal_acceleration(double threshold, double damping, DampingMode mode,
                                GridFields& fields) {
  const auto n = static_cast<std::int64_t>(fields.active.size());
  for_each_index(n, [&](std::int64_t q) {
    const auto i = static_cast<std::size_t>(fields.active[static_cast<std::size_t>(q)]);
    const double m_i = fields.mass[i];
    if (!(m_i >= threshold && m_i > 0.0)) {
      fields.acceleration[i].setZero();
      return;
    }
    // Eq. 8 on the free components only: the force along a prescribed component is reacted by
    // the constraint (e.g. the platen load), not an out-of-balance force to damp.
    common::Vec3 f_i = fields.force[i];
    common::Vec3 v_i = fields.velocity[i];
    for (int d = 0; d < 3; ++d) {
      if (fields.fixed[i] & (1u << d)) {
        f_i[d] = 0.0;
        v_i[d] = 0.0;
      }
    }
    common::Vec3 f_damped = fields.force[i];
    if (damping > 0.0) {
      if (mode == DampingMode::cundall_vector) {
        const double speed = v_i.norm();
        if (speed > 0.0) f_damped -= damping * f_i.norm() * (v_i / speed);
      } else {
        for (int d = 0; d < 3; ++d) {
          const double sign = v_i[d] > 0.0 ? 1.0 : (v_i[d] < 0.0 ? -1.0 : 0.0);
          f_damped[d] -= damping * std::abs(f_i[d]) * sign;
        }
      }
    }
    fields.acceleration[i] = f_damped / m_i;
  });
}

}  // namespace mpm
