// farm::ElasticMaterial: the material of the continuum bodies ([mpm.elastic]) in the job's units,
// and its parameter table (common/param_table.hpp), the one home of the section's keys; the model
// (farm::ElasticMicro) takes its angles in radians from to_radians().
#pragma once

#include <cmath>

#include "common/param_table.hpp"

namespace farm {

/// Linear elastic, or with a friction angle a cohesionless Drucker-Prager continuum (dilatant or
/// not, with a dilatancy cut-off or not, softening or not). The angles are in degrees, as the job
/// writes them; the defaults are a linear elastic material without a modulus (young_modulus and
/// poisson_ratio are required).
struct ElasticMaterial {
  double young_modulus = 0.0;  ///< E [Pa], > 0
  double poisson_ratio = 0.0;  ///< nu [-], in (-1, 0.5)
  /// Friction angle of the Drucker-Prager cone matched to plane-strain Mohr-Coulomb [deg], in
  /// [0, 90). 0: linear elastic (no yield surface).
  double friction_deg = 0.0;
  /// Dilatancy angle of the plastic flow, matched to plane-strain Mohr-Coulomb with the friction
  /// angle (mpm::plane_strain_cone) [deg], in [0, friction_deg]. 0: deviatoric flow; equal to
  /// friction_deg: associated flow, for which Prandtl's bearing capacity is exact.
  double dilatancy_deg = 0.0;
  /// Residual friction angle of the softening [deg], in [0, friction_deg]; read only when
  /// softening_strain > 0.
  double residual_friction_deg = 0.0;
  /// Friction softening (mpm/friction_softening.hpp): sin(phi) falls linearly with the
  /// accumulated plastic shear strain from sin(friction) to sin(residual friction), reached at
  /// softening_strain [-]. 0: no softening (perfectly plastic). > 0 needs a friction angle and no
  /// dilatancy.
  double softening_strain = 0.0;
  /// Dilatancy cut-off: the plastic volumetric strain (dilation, the sum of tr(d eps_p)) after
  /// which the flow is deviatoric, the critical state of a dense material (Vermeer & de Borst
  /// 1984; PLAXIS's "dilatancy cut-off" at a maximum void ratio) [-]. 0: none, the material
  /// dilates for ever. > 0 needs a dilatancy angle.
  double dilatancy_cutoff = 0.0;

  /// Throws common::InputError naming the job key of the first invalid entry: the ranges of
  /// kElasticMaterial, then the rules between the angles.
  void validate() const;
};

using common::Source;
using common::Unit;

/// [mpm.elastic]. The optional angles are absent as 0 (linear elastic, no dilatancy, no
/// softening); the rules between keys are the app's job rules and validate()'s.
inline constexpr auto kElasticMaterial = common::make_table<ElasticMaterial>(
    "farm::ElasticMaterial", "mpm.elastic",
    {{"young_modulus", &ElasticMaterial::young_modulus, Unit::Pressure, common::gt(0),
      Source::job_required, "Young's modulus."},
     {"poisson_ratio", &ElasticMaterial::poisson_ratio, Unit::Dimensionless, common::in_oo(-1, 0.5),
      Source::job_required, "Poisson's ratio."},
     {"friction_angle", &ElasticMaterial::friction_deg, Unit::Angle, common::in_co(0, 90),
      Source::job_optional,
      "Absent: linear elastic. Given: elastic-perfectly plastic, cohesionless Drucker-Prager cone "
      "matched to Mohr-Coulomb in plane strain (tension returns to zero stress): a frictional "
      "continuum to compare the DEM RVEs with on the same mesh (docs/design/mpm.md, Frictional "
      "continuum)."},
     {"dilatancy_angle", &ElasticMaterial::dilatancy_deg, Unit::Angle, common::in_co(0, 90),
      Source::job_optional,
      "Dilatancy angle psi of the Drucker-Prager flow, matched to Mohr-Coulomb in plane strain "
      "with friction_angle (needs it; at most friction_angle). Absent or 0: no dilatancy; equal "
      "to friction_angle: associated flow, for which Prandtl's bearing capacity is exact."},
     {"residual_friction_angle", &ElasticMaterial::residual_friction_deg, Unit::Angle,
      common::in_co(0, 90), Source::job_optional,
      "Friction softening (with softening_strain; needs friction_angle, no dilatancy): sin(phi) "
      "falls linearly with the accumulated plastic shear strain from sin(friction_angle) to "
      "sin(residual_friction_angle), at most friction_angle (docs/design/mpm.md, Frictional "
      "continuum). Absent: perfectly plastic."},
     {"softening_strain", &ElasticMaterial::softening_strain, Unit::Dimensionless, common::ge(0),
      Source::job_optional,
      "The accumulated plastic shear strain at which the friction reaches "
      "residual_friction_angle (with it; > 0 when given). Absent: no softening."},
     {"dilatancy_cutoff", &ElasticMaterial::dilatancy_cutoff, Unit::Dimensionless, common::ge(0),
      Source::job_optional,
      "Dilatancy cut-off: the plastic volumetric strain (dilation) after which the flow is "
      "deviatoric, the critical state of a dense material (needs dilatancy_angle; > 0 when "
      "given; docs/design/mpm.md, Frictional continuum). Absent: the material dilates for "
      "ever."}});

/// An angle of the job in radians, as the model uses it: deg * pi / 180, the one conversion (the
/// expression the app has always used, so that a job's results stay bit for bit).
[[nodiscard]] inline double to_radians(double deg) { return deg * M_PI / 180.0; }

/// The angles of a material in radians [rad].
struct ElasticAngles {
  double friction = 0.0;
  double dilatancy = 0.0;
  double residual_friction = 0.0;
};

/// The material's angles through to_radians.
[[nodiscard]] inline ElasticAngles to_radians(const ElasticMaterial& m) {
  return {to_radians(m.friction_deg), to_radians(m.dilatancy_deg),
          to_radians(m.residual_friction_deg)};
}

/// The degrees of an angle that an older state stored in radians (ElasticMicro versions 2 to 5):
/// near rad * 180 / pi, degrees whose to_radians() is rad exactly when there are such (the states
/// the app wrote: their radians came from the job's degrees), the shortest in decimal (the job's
/// 11.7), so that the state saved again under its job keys gives the same radians; else
/// rad * 180 / pi.
[[nodiscard]] double degrees_of_radians(double rad);

}  // namespace farm
