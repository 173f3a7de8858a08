// Plain parameter structs of the DEM module (units in the field comments) and their parameter
// tables (common/param_table.hpp): the one home of each setting's job key, unit, range, default
// and meaning. The app maps the job file onto the structs through the tables; dem parses no job
// file. Contact law: Aboul Hosn et al. 2017, Granular Matter 19(1).
#pragma once

#include <cstdint>

#include "common/param_table.hpp"

namespace dem {

/// One material for all spheres (CohFrictMat without cohesion, YADE terms in brackets). The
/// defaults are placeholders: the job file must give every entry (kMaterial).
struct Material {
  double density = 0.0;       ///< rho [kg/m^3]
  double young = 0.0;         ///< E [Pa]; k_n = 2 E R1 R2 / (R1 + R2) [N/m]
  double ks_over_kn = 0.0;    ///< k_s / k_n [-] (YADE `poisson`)
  double friction_deg = 0.0;  ///< inter-particle friction angle phi [deg], in [0, 90)
  double alpha_r = 0.0;       ///< rolling stiffness coefficient [-]: k_r = alpha_r k_s R1 R2
  double eta_r = -1.0;        ///< rolling strength coefficient [-]; < 0: no cap
  double alpha_t = 0.0;       ///< twisting stiffness coefficient [-]: k_t = alpha_t k_s R1 R2
  double eta_t = -1.0;        ///< twisting strength coefficient [-]; < 0: no cap

  /// Throws common::InputError naming the job key of the first invalid entry (kMaterial).
  void validate() const;
};

/// Numerical parameters of the integrator and neighbour search. The member initializers are the
/// defaults of the job keys too (kNumerics).
struct Numerics {
  double damping = 0.2;           ///< Cundall non-viscous damping lambda [-], in [0, 1)
  double dt_safety = 0.8;         ///< safety factor on the global-stiffness critical step [-]
  double skin_factor = 0.1;       ///< Verlet skin as a fraction of the largest radius [-]
  double skin_min_factor = 0.03;  ///< > 0: the skin adapts in [this, skin_factor] r_max [-]
  std::int64_t dt_refresh = 100;  ///< steps between critical time step refreshes [-]
  double max_skew = 0.5;          ///< re-map the cell when |c_b . c_a| / |c_a|^2 exceeds this [-]

  /// Throws common::InputError naming the job key of the first invalid entry (kNumerics).
  void validate() const;
};

using common::Source;
using common::Unit;

/// [dem.material]: YADE CohFrictMat with rolling resistance, Aboul Hosn et al. 2017.
inline constexpr auto kMaterial = common::make_table<Material>(
    "dem::Material", "dem.material",
    {{"density", &Material::density, Unit::Density, common::gt(0), Source::job_required,
      "Grain density rho."},
     {"young_modulus", &Material::young, Unit::Pressure, common::gt(0), Source::job_required,
      "Contact modulus E: kn = 2 E R1 R2 / (R1 + R2)."},
     {"stiffness_ratio", &Material::ks_over_kn, Unit::Dimensionless, common::gt(0),
      Source::job_required, "ks / kn (YADE's `poisson`)."},
     {"friction_angle", &Material::friction_deg, Unit::Angle, common::in_co(0, 90),
      Source::job_required, "Inter-particle friction angle phi."},
     {"rolling_stiffness", &Material::alpha_r, Unit::Dimensionless, common::ge(0),
      Source::job_required, "alpha_r: kr = alpha_r ks R1 R2."},
     {"rolling_strength", &Material::eta_r, Unit::Dimensionless, common::any(),
      Source::job_required,
      "eta_r: |Mr| <= eta_r min(R1, R2) Fn; a negative value means no cap (purely elastic)."},
     {"twisting.stiffness", &Material::alpha_t, Unit::Dimensionless, common::ge(0),
      Source::job_required, "alpha_t: kt = alpha_t ks R1 R2."},
     {"twisting.strength", &Material::eta_t, Unit::Dimensionless, common::any(),
      Source::job_required, "eta_t: twisting cap coefficient; negative: no cap."}});

/// [dem.numerics]: the defaults are the member initializers of Numerics.
inline constexpr auto kNumerics = common::make_table<Numerics>(
    "dem::Numerics", "dem.numerics",
    {{"damping", &Numerics::damping, Unit::Dimensionless, common::in_co(0, 1), Source::job_default,
      "Cundall non-viscous damping coefficient lambda."},
     {"timestep_safety", &Numerics::dt_safety, Unit::Dimensionless, common::in_cc(0.01, 1),
      Source::job_default,
      "Fraction of the critical time step used. At least 0.01: below, the DEM steps grow with no "
      "gain (1e-300 stalled the sample's preparation for 2,000,000 steps)."},
     {"verlet_skin", &Numerics::skin_factor, Unit::Dimensionless, common::in_oc(0, 1),
      Source::job_default,
      "Verlet skin as a fraction of the largest radius: the neighbour list keeps pairs whose gap "
      "is below it and is rebuilt when motion could close it (speed and round-off, not "
      "physics). At most 1 (a skin of one radius: a list of most of the cell's neighbours)."},
     {"verlet_skin_min", &Numerics::skin_min_factor, Unit::Dimensionless, common::in_cc(0, 1),
      Source::job_default,
      "0: the skin is verlet_skin (the fixed skin of older versions). Above 0: each RVE adapts its skin between "
      "this fraction of "
      "the largest radius and verlet_skin to how fast its spheres move (thin when they barely "
      "move, fewer pairs; wide in a flow, fewer rebuilds), from its own state: restarts, ranks "
      "and threads keep their bits (docs/design/dem.md \"Neighbour search\")."},
     {"dt_refresh", &Numerics::dt_refresh, Unit::Dimensionless, common::ge(1), Source::cpp_only,
      "Steps between critical time step refreshes."},
     {"max_skew", &Numerics::max_skew, Unit::Dimensionless, common::ge(0.5), Source::cpp_only,
      "Re-map the cell when |c_b . c_a| / |c_a|^2 exceeds this."}});

}  // namespace dem
