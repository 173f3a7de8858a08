// Test helpers: a regular plane (x, z) lattice of points and a tensor field value, the nonlocal
// averages' test fields.
#pragma once

#include <vector>

#include "common/types.hpp"

namespace mpm_test {

/// Appends nx x nz points of spacing h centred on 0 (y = 0), each of volume h^2 (unit thickness).
inline void plane_lattice(int nx, int nz, double h, std::vector<common::Vec3>& x,
                          std::vector<double>& volume) {
  for (int k = 0; k < nz; ++k) {
    for (int i = 0; i < nx; ++i) {
      x.emplace_back((i - 0.5 * (nx - 1)) * h, 0.0, (k - 0.5 * (nz - 1)) * h);
      volume.push_back(h * h);
    }
  }
}

/// A tensor with distinct entries, scaled by a: a field value that no symmetry hides.
inline common::Mat3 filled(double a) {
  common::Mat3 m;
  m << a, 2 * a, 3 * a, -a, 0.5 * a, 0.0, 0.25 * a, a, -2 * a;
  return m;
}

}  // namespace mpm_test
