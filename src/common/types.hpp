// Small shared vocabulary: vectors and tensors (Eigen), index types.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace common {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec3i = Eigen::Vector3i;
using Index = std::int64_t;

}  // namespace common
