// Sphere storage as structure-of-arrays (one vector per property), positions in Cartesian
// coordinates inside a periodic cell, velocities split into affine (L x) and fluctuating parts.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "common/types.hpp"

namespace dem {

/// Polydisperse spheres, SoA. Index = sphere id.
struct Spheres {
  std::vector<common::Vec3> x;      ///< centre [m]; wrapped into the cell at each neighbour rebuild
  std::vector<common::Vec3> u;      ///< fluctuating velocity v - L x [m/s]
  std::vector<common::Vec3> w;      ///< spin [rad/s]
  std::vector<common::Vec3> force;  ///< total contact force of the last step [N]
  std::vector<common::Vec3> torque;  ///< total contact torque of the last step [N m]
  std::vector<double> r;             ///< radius [m]
  std::vector<double> m;             ///< mass [kg]
  std::vector<double> inertia;       ///< moment of inertia 2/5 m r^2 [kg m^2]
  std::vector<std::uint8_t> fixed;   ///< 1: velocity and spin prescribed, not integrated

  [[nodiscard]] std::size_t size() const { return r.size(); }

  /// Append a sphere at rest. @param rho density [kg/m^3]
  void add(const common::Vec3& pos, double radius, double rho);
  /// Reset masses and inertia from radii and a density [kg/m^3].
  void set_density(double rho);
};

}  // namespace dem
