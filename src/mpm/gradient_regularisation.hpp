// Nonlocal strain-gradient regularisation of the macro scale: an elastic energy on the difference
// between each point's strain and its nonlocal (Gaussian) average over a material length l,
//   psi = 1/2 H sum_p V_p |e_p|^2,  de_p/dt = D_p - Dbar_p (objective: Jaumann rate),
// a nonlocal form of the second-gradient energy of Chambon et al. (2001) and of the FEM x DEM of
// Desrues et al. (2019). The materials (the RVEs) keep their own L; the energy adds the stress
// (I - N^T) H e to the internal forces. docs/design/mpm.md, "Regularisation".
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "common/types.hpp"
#include "mpm/point_average.hpp"

namespace mpm {

class GradientRegularisation {
 public:
  /// length: l [m] > 0; modulus: H [Pa] > 0 (common::InputError otherwise); average: how the
  /// nonlocal average is computed (point_average.hpp).
  GradientRegularisation(double length, double modulus, AverageKind average);

  /// One step's strain increment: e_p += dt (D_p - Dbar_p + W_p e_p - e_p W_p), D and W the
  /// symmetric and skew parts of L_p, Dbar the nonlocal average of D (same material). Returns the
  /// step's work of the regularising stress, dt sum_p V_p H e_mid : (D_p - Dbar_p) [J]. Sizes the
  /// state on the first call (zero strain). Pre: x, volume, material and L have one entry per
  /// point, the same points as before.
  double update(const std::vector<common::Vec3>& x, const std::vector<double>& volume,
                const std::vector<std::int32_t>& material, const std::vector<common::Mat3>& L,
                double dt);

  /// stress[p] += H e_p - (N^T H e)_p: the stress whose internal forces are the energy's (with
  /// the positions and volumes of the last update). Pre: as update.
  void add_force_stress(const std::vector<common::Vec3>& x, const std::vector<double>& volume,
                        const std::vector<std::int32_t>& material,
                        std::vector<common::Mat3>& stress);

  /// Accumulated strain fluctuation e of each point [-] (empty before the first update).
  [[nodiscard]] const std::vector<common::Mat3>& strain() const { return strain_; }
  /// Restores the state (a checkpoint's); n entries, one per point.
  void set_strain(std::vector<common::Mat3> strain) { strain_ = std::move(strain); }
  [[nodiscard]] double length() const { return average_->length(); }
  [[nodiscard]] double modulus() const { return modulus_; }

 private:
  std::unique_ptr<PointAverage> average_;
  double modulus_;
  std::vector<common::Mat3> strain_;        ///< e [-]
  std::vector<common::Mat3> rate_;          ///< D [1/s] (scratch)
  std::vector<common::Mat3> average_rate_;  ///< Dbar [1/s] (scratch)
  std::vector<common::Mat3> tau_;           ///< H e, then N^T H e [Pa] (scratch)
  std::vector<common::Mat3> smoothed_;      ///< (scratch)
};

}  // namespace mpm
