// Periodic cell: matrix H (columns = cell vectors) deformed by a full velocity gradient L (spin
// included) as YADE's homogeneous deformation, H <- (I + L dt) H.
#pragma once

#include <Eigen/Dense>

#include "common/types.hpp"

namespace dem {

struct PeriodicCell {
  common::Mat3 h = common::Mat3::Identity();  ///< cell matrix, columns are the cell vectors [m]
  common::Mat3 l = common::Mat3::Zero();      ///< velocity gradient applied this step [1/s]

  [[nodiscard]] double volume() const { return h.determinant(); }
  /// Perpendicular width of the cell across cell vector a [m].
  [[nodiscard]] double width(int a) const;
  /// One step of homogeneous deformation.
  void deform(double dt) { h = h + (dt * l) * h; }
};

}  // namespace dem
