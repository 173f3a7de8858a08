// Contacts SoA helpers: resize and the per-sphere pair lists (fixed order for the force sums).
#include "dem/contacts.hpp"

#include <limits>
#include <string>

#include "common/errors.hpp"

namespace dem {

void Contacts::resize(std::size_t n) {
  i.resize(n);
  j.resize(n);
  k.resize(n, common::Vec3i::Zero());
  active.resize(n, 0);
  tan_phi.resize(n, 0.0);
  hist.resize(n);
  force.resize(n, common::Vec3::Zero());
  torque_i.resize(n, common::Vec3::Zero());
  torque_j.resize(n, common::Vec3::Zero());
  branch.resize(n, common::Vec3::Zero());
  twist = Twist::unknown;
}

void Contacts::classify_twist() {
  if (twist != Twist::unknown) return;
  bool some = false;
  for (std::size_t p = 0; p < size() && !some; ++p) {
    some = hist.twist[0][p] != 0.0 || hist.twist[1][p] != 0.0 || hist.twist[2][p] != 0.0;
  }
  twist = some ? Twist::some : Twist::none;
}

void Contacts::build_sphere_lists(std::size_t n_spheres) {
  if (size() >= static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    throw common::InputError("dem: more than 2^31 - 1 Verlet pairs in one cell (" +
                             std::to_string(size()) + ")");
  }
  sphere_offset.assign(n_spheres + 1, 0);
  for (std::size_t p = 0; p < size(); ++p) {
    ++sphere_offset[i[p] + 1];
    ++sphere_offset[j[p] + 1];
  }
  for (std::size_t s = 0; s < n_spheres; ++s) sphere_offset[s + 1] += sphere_offset[s];
  sphere_pairs.assign(sphere_offset[n_spheres], 0);
  std::vector<std::int64_t> fill(sphere_offset.begin(), sphere_offset.end() - 1);
  for (std::size_t p = 0; p < size(); ++p) {
    const auto ip = static_cast<std::int32_t>(p);
    sphere_pairs[fill[i[p]]++] = ip;
    sphere_pairs[fill[j[p]]++] = -ip - 1;
  }
}

}  // namespace dem
