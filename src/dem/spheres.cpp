// Spheres SoA helpers.
#include "dem/spheres.hpp"

#include <numbers>

namespace dem {

void Spheres::add(const common::Vec3& pos, double radius, double rho) {
  x.push_back(pos);
  u.push_back(common::Vec3::Zero());
  w.push_back(common::Vec3::Zero());
  force.push_back(common::Vec3::Zero());
  torque.push_back(common::Vec3::Zero());
  r.push_back(radius);
  const double mass = rho * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  m.push_back(mass);
  inertia.push_back(0.4 * mass * radius * radius);
  fixed.push_back(0);
}

void Spheres::set_density(double rho) {
  for (std::size_t i = 0; i < r.size(); ++i) {
    m[i] = rho * 4.0 / 3.0 * std::numbers::pi * r[i] * r[i] * r[i];
    inertia[i] = 0.4 * m[i] * r[i] * r[i];
  }
}

}  // namespace dem
