// farm::DemMicro: the DEM RVE of Duverger et al. 2022 (section 2.2, eqs. 11-12) behind the
// MicroModel contract: wraps dem::Rve and turns an exhausted guard into a failure.
#pragma once

#include <functional>

#include "dem/packing_io.hpp"
#include "dem/rve.hpp"
#include "farm/micro_model.hpp"

namespace farm {

struct DemMicroParams {
  dem::RveParams rve;  ///< material, numerics, quasi-static step control (dem/rve.hpp)
  /// dem::RveGuard bits that make a step FAIL (common::NumericalError) instead of only being
  /// reported. Default: kGuardStepCap (T_p was cut short: the step is no longer quasi-static).
  std::uint32_t fail_guards = dem::kGuardStepCap;
};

class DemMicro final : public MicroModel {
 public:
  DemMicro(dem::Rve rve, std::uint32_t fail_guards);
  MicroReport step(const common::Mat3& L, double dt) override;
  [[nodiscard]] common::Mat3 stress() const override { return rve_.stress(); }
  [[nodiscard]] MicroReport report() const override;
  /// dem::measure of the RVE's state (fabric, Z without rattlers, unbalanced force, kinetic
  /// energy): one more pass over the contacts, for output rows only.
  [[nodiscard]] MicroMeasures measures() const override;
  /// dem::vtk_view of the RVE's simulation (spheres, contacts, cell; forces of the last step).
  [[nodiscard]] std::vector<ViewFile> grain_view(const std::string& stem) const override;
  /// dem::Rve::save fields plus farm/dem_fail_guards.
  void save(common::StateWriter& writer) const override;
  /// Number of spheres.
  [[nodiscard]] double cost_estimate() const override {
    return static_cast<double>(rve_.num_spheres());
  }
  /// Upper bound: sqrt(E / rho_s) with the contact modulus E and the solid density [m/s]
  /// (a packing is softer and lighter per volume than its grains' contacts suggest).
  [[nodiscard]] double wave_speed() const override;
  /// dem::Rve::dilute: a solid fraction below dem.coupling.disconnect_fraction.
  [[nodiscard]] bool dilute() const override { return rve_.dilute(); }

  static std::unique_ptr<MicroModel> load(const common::StateReader& reader);
  /// A MicroKind building the RVE of point id from packing_of(id) (e.g. one shared packing,
  /// or one per id) with `params`.
  static MicroKind kind(const DemMicroParams& params,
                        std::function<dem::Packing(std::int64_t id)> packing_of);

  [[nodiscard]] const dem::Rve& rve() const { return rve_; }

 private:
  dem::Rve rve_;
  std::uint32_t fail_guards_;
};

}  // namespace farm
