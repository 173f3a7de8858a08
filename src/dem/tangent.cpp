// Contact-stiffness tangent of a periodic packing (see header).
#include "dem/tangent.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "common/tensor.hpp"

namespace dem {

using common::Mat3;
using common::Vec3;

namespace {

using Row9 = Eigen::Matrix<double, 9, 1>;

constexpr std::array<std::array<int, 2>, 6> kPair = {
    {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}}};

/// The upper triangle of a 6 x 6 (21 entries, row by row) and of a 3 x 3 (6 entries).
constexpr std::array<std::array<int, 2>, 21> kUpper6 = [] {
  std::array<std::array<int, 2>, 21> u{};
  int k = 0;
  for (int a = 0; a < 6; ++a)
    for (int e = a; e < 6; ++e) u[static_cast<std::size_t>(k++)] = {a, e};
  return u;
}();
constexpr std::array<std::array<int, 2>, 6> kUpper3 = {
    {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}}};

/// acc[k] += wm[a_k] * m[e_k] for the 21 entries, written out (index_sequence): the sums live in
/// registers instead of a matrix in memory that every contact loads and stores. Each entry is
/// the same product added in the same contact order as f(a, e) += (w m_a) m_e: the same bits.
template <std::size_t... K>
inline void add_f(std::array<double, 21>& acc, const std::array<double, 6>& wm,
                  const std::array<double, 6>& m, std::index_sequence<K...> /*unused*/) {
  ((acc[K] +=
    wm[static_cast<std::size_t>(kUpper6[K][0])] * m[static_cast<std::size_t>(kUpper6[K][1])]),
   ...);
}

template <std::size_t... K>
inline void add_b(std::array<double, 6>& acc, const std::array<double, 3>& wn,
                  const std::array<double, 3>& n, std::index_sequence<K...> /*unused*/) {
  ((acc[K] +=
    wn[static_cast<std::size_t>(kUpper3[K][0])] * n[static_cast<std::size_t>(kUpper3[K][1])]),
   ...);
}

}  // namespace

Tangent contact_stiffness_tangent(const Simulation& sim) {
  const Contacts& c = sim.contacts();
  const Spheres& s = sim.spheres();
  // The unsymmetrised sum A(ij, kl) = sum_c K_ik d_l d_j, K = k_n n n + a k_s (I - n n), d = |d| n:
  // the stress increment (1/V) sum (K deps d) (x) d of affine contact displacements deps d. It is
  // A(ij, kl) = F_ijkl + delta_ik B_jl with F = sum |d|^2 (k_n - a k_s) n n n n (symmetric in all
  // four indices) and B = sum |d|^2 a k_s n n, so each contact adds to the 21 entries of F on the
  // 6 index pairs and the 6 of B instead of the 81 of A (summed over the 81, it took a fifth of
  // a spared footing's run time). Summed in contact order (deterministic, one thread: one pass
  // over the contacts), each entry in a register of its own (add_f, add_b).
  // First the normal and the two weights of every active contact (independent contacts: their
  // square roots and divisions overlap), then the sums.
  struct Term {
    double n[3];
    double w_normal;
    double w_shear;
  };
  thread_local std::vector<Term> terms;
  terms.clear();
  for (std::size_t p = 0; p < c.size(); ++p) {
    if (c.active[p] == 0) continue;
    const Vec3& d = c.branch[p];
    const double len2 = d.squaredNorm();
    const double len = std::sqrt(len2);
    if (!(len > 0.0)) continue;
    const Vec3 n = d / len;
    const double shear_factor =
        (s.r[static_cast<std::size_t>(c.i[p])] + s.r[static_cast<std::size_t>(c.j[p])]) / len;
    const ContactProps pr = sim.contact_props(p);
    const double kt = shear_factor * pr.ks;
    terms.push_back({{n(0), n(1), n(2)}, len2 * (pr.kn - kt), len2 * kt});
  }
  std::array<double, 21> f21{};
  std::array<double, 6> b6{};
  for (const Term& t : terms) {
    std::array<double, 6> m{};
    std::array<double, 6> wm{};
    for (std::size_t a = 0; a < 6; ++a) {
      m[a] = t.n[kPair[a][0]] * t.n[kPair[a][1]];
      wm[a] = t.w_normal * m[a];
    }
    add_f(f21, wm, m, std::make_index_sequence<21>{});
    const std::array<double, 3> nn = {t.n[0], t.n[1], t.n[2]};
    const std::array<double, 3> wn = {t.w_shear * t.n[0], t.w_shear * t.n[1], t.w_shear * t.n[2]};
    add_b(b6, wn, nn, std::make_index_sequence<6>{});
  }
  Eigen::Matrix<double, 6, 6> f = Eigen::Matrix<double, 6, 6>::Zero();  // upper triangle first
  for (std::size_t k = 0; k < 21; ++k) f(kUpper6[k][0], kUpper6[k][1]) = f21[k];
  Mat3 b = Mat3::Zero();
  for (std::size_t k = 0; k < 6; ++k) b(kUpper3[k][0], kUpper3[k][1]) = b6[k];
  // The index pair (i, j) -> its row of f; f and b filled out by symmetry.
  constexpr std::array<std::array<int, 3>, 3> kVoigt = {{{0, 3, 4}, {3, 1, 5}, {4, 5, 2}}};
  f.triangularView<Eigen::StrictlyLower>() = f.transpose();
  b.triangularView<Eigen::StrictlyLower>() = b.transpose();
  // Minor symmetries (symmetric stress out, symmetric strain in): F has them already; the
  // delta_ik B_jl part is averaged over (i, j) and (k, l).
  Tangent t;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int kk = 0; kk < 3; ++kk) {
        for (int l = 0; l < 3; ++l) {
          const double delta_b = (i == kk ? b(j, l) : 0.0) + (j == kk ? b(i, l) : 0.0) +
                                 (i == l ? b(j, kk) : 0.0) + (j == l ? b(i, kk) : 0.0);
          t(3 * i + j, 3 * kk + l) = f(kVoigt[i][j], kVoigt[kk][l]) + 0.25 * delta_b;
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
