// Contact-stiffness tangent of a periodic packing (see header).
#include "dem/tangent.hpp"

#include <array>

#include "common/tensor.hpp"

namespace dem {

using common::Mat3;
using common::Vec3;

namespace {
using Row9 = Eigen::Matrix<double, 9, 1>;
}  // namespace

Tangent contact_stiffness_tangent(const Simulation& sim) {
  const Contacts& c = sim.contacts();
  const Spheres& s = sim.spheres();
  // Unsymmetrised sum A(ij, kl) = sum_c K_ik d_l d_j with K = k_n n n + a k_s (I - n n): the
  // stress increment (1/V) sum (K deps d) (x) d of affine contact displacements deps d. Summed in
  // pair order (deterministic, one thread: one pass over the contacts).
  Tangent a = Tangent::Zero();
  for (std::size_t p = 0; p < c.size(); ++p) {
    if (c.active[p] == 0) continue;
    const Vec3& d = c.branch[p];
    const double len = d.norm();
    if (!(len > 0.0)) continue;
    const Vec3 n = d / len;
    const double shear_factor =
        (s.r[static_cast<std::size_t>(c.i[p])] + s.r[static_cast<std::size_t>(c.j[p])]) / len;
    const ContactProps pr = sim.contact_props(p);
    const double kt = shear_factor * pr.ks;
    const Mat3 k = (pr.kn - kt) * (n * n.transpose()) + kt * Mat3::Identity();
    const Mat3 dd = d * d.transpose();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        for (int kk = 0; kk < 3; ++kk) {
          const double kik = k(i, kk);
          for (int l = 0; l < 3; ++l) a(3 * i + j, 3 * kk + l) += kik * dd(l, j);
        }
      }
    }
  }
  // Minor symmetries: symmetric stress out, symmetric strain in.
  Tangent t = Tangent::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int kk = 0; kk < 3; ++kk) {
        for (int l = 0; l < 3; ++l) {
          t(3 * i + j, 3 * kk + l) = 0.25 * (a(3 * i + j, 3 * kk + l) + a(3 * j + i, 3 * kk + l) +
                                             a(3 * i + j, 3 * l + kk) + a(3 * j + i, 3 * l + kk));
        }
      }
    }
  }
  return t / sim.cell().volume();
}

Mat3 apply_tangent(const Tangent& c, const Mat3& deps) {
  Row9 e;
  common::row_major_out(e.data()) = deps;
  const Row9 s = c * e;
  return common::row_major(s.data());
}

}  // namespace dem
