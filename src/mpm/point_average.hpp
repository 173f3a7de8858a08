// The smoothing operator of the macro scale's regularisation, as an interface: a normalised
// Gaussian average of a per-point tensor over a material length l and its adjoint in the
// volume-weighted product. Two implementations: the exact sum over the pairs of points
// (nonlocal_average.hpp) and the same kernel on an auxiliary lattice (lattice_average.hpp).
// docs/design/mpm.md, "Regularisation". Called a few times per MPM step, never per contact.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "common/choice_table.hpp"
#include "common/types.hpp"

namespace mpm {

/// The Gaussian kernel is cut at this many lengths (its weight there: exp(-4.5) = 1.1 %) [-].
inline constexpr double kNonlocalCutoff = 3.0;

/// Lbar_p = sum_q w_pq V_q L_q / W_p, W_p = sum_q w_pq V_q, over the points q of p's group (a
/// group is a material: materials are never mixed), w_pq = w_qp a Gaussian of standard deviation
/// l cut near 3 l. A homogeneous field is unchanged everywhere.
class PointAverage {
 public:
  virtual ~PointAverage() = default;

  /// Sets up the weights for the positions x and volumes V (> 0) of the points, each of a group:
  /// the state apply and apply_adjoint use until the next prepare. Pre: x, volume and group have
  /// the same size (common::NumericalError otherwise).
  virtual void prepare(const std::vector<common::Vec3>& x, const std::vector<double>& volume,
                       const std::vector<std::int32_t>& group) = 0;
  /// True when the last prepare saw exactly these positions and volumes (bit for bit).
  [[nodiscard]] virtual bool prepared_for(const std::vector<common::Vec3>& x,
                                          const std::vector<double>& volume) const = 0;
  /// out[p] = Lbar_p (out is resized; it must not alias in). Pre: prepared, for in.size()
  /// points (common::NumericalError otherwise).
  virtual void apply(const std::vector<common::Mat3>& in, std::vector<common::Mat3>& out) = 0;
  /// The adjoint (transpose) of apply in the volume-weighted inner product: out[q] = sum_p w_pq
  /// V_p in[p] / W_p: sum_p V_p s_p : (N L)_p = sum_q V_q (N^T s)_q : L_q for any fields s, L,
  /// so a stress paired with averaged rates becomes one of internal forces. Keeps sum_q V_q
  /// out[q] = sum_p V_p in[p]. Pre: as apply.
  virtual void apply_adjoint(const std::vector<common::Mat3>& in,
                             std::vector<common::Mat3>& out) = 0;
  [[nodiscard]] virtual double length() const = 0;

  /// prepare, then apply.
  void apply(const std::vector<common::Vec3>& x, const std::vector<double>& volume,
             const std::vector<std::int32_t>& group, const std::vector<common::Mat3>& in,
             std::vector<common::Mat3>& out) {
    prepare(x, volume, group);
    apply(in, out);
  }
  /// prepare, then apply_adjoint.
  void apply_adjoint(const std::vector<common::Vec3>& x, const std::vector<double>& volume,
                     const std::vector<std::int32_t>& group, const std::vector<common::Mat3>& in,
                     std::vector<common::Mat3>& out) {
    prepare(x, volume, group);
    apply_adjoint(in, out);
  }
};

/// How the average is computed (job key mpm.regularisation.average).
enum class AverageKind {
  pairs,    ///< the exact sum over the pairs of points within 3 l (NonlocalAverage)
  lattice,  ///< through an auxiliary lattice of spacing l / 3 (LatticeAverage; the default)
};
inline constexpr std::array<common::Named<AverageKind>, 2> kAverageKindNames{
    {{"pairs", AverageKind::pairs}, {"lattice", AverageKind::lattice}}};

/// The operator of that kind for the length l [m] > 0 (common::InputError otherwise).
[[nodiscard]] std::unique_ptr<PointAverage> make_point_average(AverageKind kind, double length);

}  // namespace mpm
