// Nonlocal (integral) average of a per-point tensor over a material length l (Bazant & Jirasek
// 2002, J. Eng. Mech. 128) and its adjoint, summed over the pairs of points: one operator of the
// macro scale's regularisation (point_average.hpp, gradient_regularisation.hpp;
// docs/design/mpm.md, "Regularisation").
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "common/types.hpp"
#include "mpm/point_average.hpp"

namespace mpm {

/// Lbar_p = sum_q w_pq V_q L_q / sum_q w_pq V_q over the points q of the same group as p (a group
/// is a material: materials are never mixed), with w_pq = exp(-|x_p - x_q|^2 / (2 l^2)) for
/// |x_p - x_q| < 3 l and 0 beyond: a normalised Gaussian of standard deviation l. A homogeneous
/// field is unchanged everywhere; a linear one wherever the kernel is not cut by the material's
/// boundary (there the average is one-sided). Each point's sum runs over its neighbours in a fixed
/// order (bins of side 3 l, then point order): the result depends on neither the thread count
/// nor the order of the calls.
class NonlocalAverage final : public PointAverage {
 public:
  using PointAverage::apply;
  using PointAverage::apply_adjoint;

  /// length: l [m], > 0 (common::InputError otherwise).
  explicit NonlocalAverage(double length);

  /// Finds each point's neighbours (same group, within 3 l) and their weights w_pq for the
  /// positions x and volumes V: the state apply and apply_adjoint use until the next prepare.
  /// Memory: one index and one weight per pair (in plane strain with 4 points per cell and l = 3
  /// cells, about 1,000 pairs per point). Pre: x, volume and group have the same size (common::
  /// NumericalError otherwise), volumes > 0.
  void prepare(const std::vector<common::Vec3>& x, const std::vector<double>& volume,
               const std::vector<std::int32_t>& group) override;
  [[nodiscard]] bool prepared_for(const std::vector<common::Vec3>& x,
                                  const std::vector<double>& volume) const override {
    return prepared_ && x == x_ && volume == volume_;
  }
  /// With the prepared neighbours (PointAverage::apply).
  void apply(const std::vector<common::Mat3>& in, std::vector<common::Mat3>& out) override;
  /// With the prepared neighbours: q's own row lists its p's (PointAverage::apply_adjoint).
  void apply_adjoint(const std::vector<common::Mat3>& in, std::vector<common::Mat3>& out) override;
  [[nodiscard]] double length() const override { return length_; }

 private:
  /// fn(q, r^2) for every q of p's group within 3 l of p, p included, in the fixed order.
  template <class Fn>
  void for_neighbours(std::size_t p, const std::vector<common::Vec3>& x,
                      const std::vector<std::int32_t>& group, Fn&& fn) const;

  double length_;
  bool prepared_ = false;
  std::vector<std::pair<std::int64_t, std::int64_t>> bins_;  ///< (bin key, point), sorted
  common::Vec3 lo_ = common::Vec3::Zero();                   ///< the bins' origin [m]
  std::int64_t nb_[3] = {1, 1, 1};                           ///< bins along each axis
  std::vector<std::int64_t> offset_;  ///< point p's pairs: [offset_[p], offset_[p + 1])
  std::vector<std::int32_t> index_;   ///< the neighbour q of each pair
  std::vector<double> weight_;        ///< w_pq V_q of each pair [m^3]
  std::vector<common::Vec3> x_;       ///< x_p at prepare [m]
  std::vector<double> volume_;        ///< V_p at prepare [m^3]
  std::vector<double> weight_sum_;    ///< W_p [m^3]
};

}  // namespace mpm
