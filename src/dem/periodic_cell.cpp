// PeriodicCell geometry helpers.
#include "dem/periodic_cell.hpp"

#include <cmath>

namespace dem {

double PeriodicCell::width(int a) const {
  const common::Vec3 b = h.col((a + 1) % 3);
  const common::Vec3 c = h.col((a + 2) % 3);
  return std::abs(volume()) / b.cross(c).norm();
}

}  // namespace dem
