// Hypoelastic isotropic linear elasticity with the Jaumann rate, integrated with the
// Hughes-Winget incrementally objective scheme (Hughes & Winget 1980, IJNME 15, 1862-1867).
#pragma once

#include <string_view>
#include <vector>

#include "common/state_io.hpp"

#include "mpm/material_model.hpp"

namespace mpm {

/// sigma_{n+1} = Q sigma_n Q^T + dt (lambda tr(D) I + 2 mu D), D = sym(L), W = skew(L),
/// Q = (I - dt W / 2)^-1 (I + dt W / 2) (exactly orthogonal: rotation by 2 atan(|w| dt / 2)).
/// A pure spin rotates the stress without changing its invariants; a rigid translation leaves
/// it unchanged. The model keeps one stress per point id (ids must be >= 0; storage grows to
/// the largest id seen).
class LinearElastic final : public MaterialModel {
 public:
  /// E [Pa] > 0, nu in (-1, 1/2), density [kg/m^3] > 0 (only for the wave speed); every point
  /// starts from initial_stress [Pa, tension positive]. Throws common::InputError otherwise.
  LinearElastic(double youngs_modulus, double poisson_ratio, double density,
                const common::Mat3& initial_stress = common::Mat3::Zero());

  void update_stress(std::span<const std::int64_t> ids, std::span<const common::Mat3> L, double dt,
                     std::span<common::Mat3> stress) override;
  /// P-wave speed sqrt((lambda + 2 mu) / rho) [m/s].
  double wave_speed() const override;
  /// Writes the state as the field <prefix>stress: 9 doubles per id (row-major), ids 0 .. max id
  /// seen (the owner calls it next to Solver::save; the parameters are the owner's).
  void save(common::StateWriter& writer, std::string_view prefix) const;
  /// Reads back what save wrote. Throws common::InputError naming a missing or malformed field.
  void load(const common::StateReader& reader, std::string_view prefix);

  /// Current stress of one point id [Pa] (initial_stress if never updated).
  [[nodiscard]] common::Mat3 stress(std::int64_t id) const;
  /// Overrides the stored stress of one point id [Pa].
  void set_stress(std::int64_t id, const common::Mat3& stress);

  double lambda() const { return lambda_; }  ///< [Pa]
  double mu() const { return mu_; }          ///< [Pa]

 private:
  void ensure(std::int64_t id);

  double lambda_;
  double mu_;
  double density_;
  common::Mat3 initial_;
  std::vector<common::Mat3> stress_;
};

}  // namespace mpm
