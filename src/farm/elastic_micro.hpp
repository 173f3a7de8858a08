// farm::ElasticMicro: a cheap deterministic continuum micro model (hypoelastic, Jaumann rate,
// Hughes-Winget objective update) that exercises the farm's plumbing without DEM; with a friction
// angle it is elastic-perfectly plastic (cohesionless Drucker-Prager, dilatant or not,
// mpm/drucker_prager.hpp): the frictional continuum that the DEM RVEs are compared with on the
// same mesh. Not a model of sand to replace the RVEs: a reference, and a tool for protocol,
// restart and balancing tests.
#pragma once

#include "common/tensor.hpp"
#include "farm/elastic_material.hpp"
#include "farm/micro_model.hpp"

namespace farm {

/// Version of ElasticMicro's state (field elastic/version; docs/reference/checkpoint.md). 1 (no
/// field): positional arrays elastic/params and elastic/int_params; 2: one named field per
/// parameter; 3: adds elastic/params/friction_angle and elastic/free_volume (a version-2 state is
/// read as friction_angle = 0, free volume 0); 4: adds elastic/params/dilatancy_angle (a version-2
/// or 3 state is read as dilatancy_angle = 0); 5: adds elastic/params/residual_friction_angle,
/// elastic/params/softening_strain and elastic/plastic_shear_strain (an older state is read
/// without softening: softening_strain = 0, residual_friction_angle = friction_angle); 6: the
/// material's parameters under their job keys (kElasticMaterial: elastic/params/young_modulus,
/// the angles in degrees), where 2 to 5 named them after C++ members (elastic/params/young) and
/// stored the angles in radians (read as the model's radians, unconverted); 7: adds
/// elastic/params/dilatancy_cutoff and elastic/plastic_volumetric_strain (a version-6 state is read
/// without a cut-off and with no plastic dilation so far).
inline constexpr std::int64_t kElasticStateVersion = 7;

struct ElasticMicroParams {
  ElasticMaterial material;  ///< [mpm.elastic]: moduli, angles [deg], softening
  double density = 0.0;      ///< rho [kg/m^3], > 0 (wave speed only)
  double void_ratio0 = 0.6;  ///< initial void ratio, carried by the volume change [-]
  common::Mat3 initial_stress = common::Mat3::Zero();  ///< tension positive [Pa]
  /// Cost knob: every step is split into this many equal sub-increments (>= 1). Gives RVEs of
  /// different cost for balancing tests; the stress depends on it (it is part of the model).
  std::int64_t substeps = 1;
  /// Fault injection for failure tests: the RVE with this id throws common::NumericalError at
  /// its step number fail_step (1-based). -1: never.
  std::int64_t fail_id = -1;
  std::int64_t fail_step = -1;
  /// Throws common::InputError naming the first invalid entry (the material's: its job key).
  void validate() const;
};

class ElasticMicro final : public MicroModel {
 public:
  ElasticMicro(std::int64_t id, const ElasticMicroParams& params);
  /// The same with its own initial stress (a geostatic body: one stress per point) [Pa].
  ElasticMicro(std::int64_t id, const ElasticMicroParams& params,
               const common::Mat3& initial_stress);
  MicroReport step(const common::Mat3& L, double dt) override;
  [[nodiscard]] common::Mat3 stress() const override { return stress_; }
  /// p and q of the stress, e = (1 + e0) J - 1, Z = 0.
  [[nodiscard]] MicroReport report() const override;
  /// No grains: MicroMeasures::none() (NaN: fabric, Z without rattlers, unbalanced force and
  /// kinetic energy are not defined for a continuum).
  [[nodiscard]] MicroMeasures measures() const override { return MicroMeasures::none(); }
  /// Named fields (docs/reference/checkpoint.md): elastic/version, elastic/id,
  /// elastic/params/<key> (the rows of kElasticMaterial under their job keys, common/
  /// state_params.hpp), elastic/params/<name> (the other members of ElasticMicroParams),
  /// elastic/stress, elastic/j, elastic/free_volume, elastic/plastic_shear_strain,
  /// elastic/plastic_volumetric_strain, elastic/steps.
  void save(common::StateWriter& writer) const override;
  [[nodiscard]] double cost_estimate() const override {
    return static_cast<double>(params_.substeps);
  }
  /// P-wave speed sqrt((lambda + 2 mu) / rho) [m/s].
  [[nodiscard]] double wave_speed() const override;

  /// Rebuilds from save(), or from a state of versions 2 to 6 (versions 2 to 5 with the radians
  /// they stored
  /// and the degrees of the parameters from degrees_of_radians); throws common::InputError naming a
  /// missing or malformed field, or the version found and the ones this build reads.
  static std::unique_ptr<MicroModel> load(const common::StateReader& reader);
  /// A MicroKind creating ElasticMicro(id, params) for every id.
  static MicroKind kind(const ElasticMicroParams& params);

 private:
  std::int64_t id_;
  ElasticMicroParams params_;
  /// The angles the model uses [rad]: to_radians(params_.material), or those an older state
  /// stored.
  ElasticAngles angles_;
  common::Mat3 stress_;
  /// One sub-step of the frictional model: elastic predictor, return onto the Drucker-Prager
  /// cone; a tensile trial returns to zero stress and the dilation beyond the elastic unloading
  /// goes to the free volume; while it is positive the material is disconnected (stress-free),
  /// and a compression closes it before the material carries stress again (Dunatunga & Kamrin
  /// 2015, as dem.coupling.contact_loss = "disconnected" does for an RVE). The flow is dilatant
  /// while the plastic dilation is below the material's cut-off at the sub-step's start, then
  /// deviatoric.
  /// @param update the elastic predictor of the sub-step (L over h)
  /// @param volumetric ln det(I + h L) of the sub-step [-]
  void frictional_substep(const common::HughesWinget& update, const common::Mat3& L, double h,
                          double volumetric);

  double j_ = 1.0;              ///< volume ratio V / V0 [-]
  double free_volume_ = 0.0;    ///< ln(V / V_connected) >= 0 of a disconnected material [-]
  double plastic_shear_ = 0.0;  ///< accumulated plastic shear strain of the softening [-]
  /// Accumulated plastic volumetric strain, sum of tr(d eps_p) of the dilatant returns [-].
  double plastic_dilation_ = 0.0;
  std::int64_t steps_ = 0;
};

}  // namespace farm
