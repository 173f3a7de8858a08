// The nonlocal average of the regularisation computed through an auxiliary lattice: the points'
// volume-weighted tensors are spread to a regular lattice of spacing s = l / 3 by linear (tent)
// weights, smoothed there by a separable Gaussian, and read back by the same weights. Its cost
// grows as the points plus the lattice's nodes times 3 l / s per axis, instead of the points
// times their neighbours within 3 l (NonlocalAverage): docs/design/mpm.md, "Regularisation".
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "common/types.hpp"
#include "mpm/point_average.hpp"

namespace mpm {

/// Lattice spacing s = l / kLatticePerLength [-].
inline constexpr double kLatticePerLength = 3.0;
/// The most lattice nodes one prepare may set up (points spread much farther than l: refused with
/// common::NumericalError rather than filling the memory; the pairs average has no such bound).
inline constexpr std::int64_t kMaxLatticeNodes = 64LL * 1024 * 1024;

/// w_pq = sum_{u,v} c_up G_uv c_vq: c the tent weights of the points on the lattice nodes, G the
/// product over the axes of g(k s) = exp(-(k s)^2 / (2 lg^2)) for |k| s <= 3 l, with lg^2 = l^2 -
/// s^2 / 3 (the two tents add s^2 / 6 each: the kernel's variance per axis stays l^2). Symmetric
/// (w_pq = w_qp), so the adjoint is exact; a homogeneous field is unchanged to rounding; a linear
/// one wherever the kernel is whole, to the points' sampling of the lattice (second order). The
/// sums run in a fixed order (points in index order onto the lattice, the lattice's lines each
/// on its own): the result depends on neither the thread count nor the order of the calls.
class LatticeAverage final : public PointAverage {
 public:
  using PointAverage::apply;
  using PointAverage::apply_adjoint;

  /// length: l [m], > 0 (common::InputError otherwise).
  explicit LatticeAverage(double length);

  /// The lattice over the points' bounding box, each point's cell and tent weights, and the
  /// kernel sums W_p. Pre: as PointAverage::prepare; at most kMaxLatticeNodes nodes (common::
  /// NumericalError naming the box otherwise).
  void prepare(const std::vector<common::Vec3>& x, const std::vector<double>& volume,
               const std::vector<std::int32_t>& group) override;
  [[nodiscard]] bool prepared_for(const std::vector<common::Vec3>& x,
                                  const std::vector<double>& volume) const override {
    return prepared_ && x == x_ && volume == volume_;
  }
  void apply(const std::vector<common::Mat3>& in, std::vector<common::Mat3>& out) override;
  void apply_adjoint(const std::vector<common::Mat3>& in, std::vector<common::Mat3>& out) override;
  [[nodiscard]] double length() const override { return length_; }
  /// The lattice spacing s [m].
  [[nodiscard]] double spacing() const { return spacing_; }

 private:
  /// store(p, sum_u c_up (G f)_u) for the points of every group, one group at a time, with
  /// f_u = sum_q c_uq value(q): the smoothing of C per-point numbers (value(q, double[C])).
  template <int C, class Value, class Store>
  void smooth(Value&& value, Store&& store);
  /// The separable Gaussian on the lattice field f (nodes x C doubles, node-major), axis by axis.
  void convolve(std::vector<double>& f, int components);

  double length_;
  double spacing_;
  std::vector<double> taps_;  ///< g(k s), k = 0..K
  bool prepared_ = false;
  common::Vec3 lo_ = common::Vec3::Zero();  ///< the lattice's origin [m]
  std::array<std::int64_t, 3> n_{2, 2, 2};  ///< nodes along each axis (>= 2)
  std::vector<std::int64_t> corner_;        ///< each point's lower corner node
  std::vector<common::Vec3> frac_;          ///< each point's position in its lattice cell [0, 1]
  std::vector<std::int32_t> slot_;          ///< each point's group, as an index into groups_
  std::size_t groups_ = 0;                  ///< how many groups
  std::vector<common::Vec3> x_;             ///< x_p at prepare [m]
  std::vector<double> volume_;              ///< V_p at prepare [m^3]
  std::vector<double> weight_sum_;          ///< W_p [m^3]
  std::vector<double> field_;               ///< scratch: the lattice field
  std::vector<double> line_;                ///< scratch: one line of it
};

}  // namespace mpm
