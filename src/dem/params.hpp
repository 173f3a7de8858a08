// Plain parameter structs of the DEM module (units in the field comments). The app maps the job
// file onto them; dem parses no job file. Contact law: Aboul Hosn et al. 2017, Granular Matter
// 19(1).
#pragma once

#include <cstdint>

namespace dem {

/// One material for all spheres (CohFrictMat without cohesion, YADE terms in brackets).
struct Material {
  double density = 0.0;       ///< rho [kg/m^3]
  double young = 0.0;         ///< E [Pa]; k_n = 2 E R1 R2 / (R1 + R2) [N/m]
  double ks_over_kn = 0.0;    ///< k_s / k_n [-] (YADE `poisson`)
  double friction_deg = 0.0;  ///< inter-particle friction angle phi [deg], in [0, 90)
  double alpha_r = 0.0;       ///< rolling stiffness coefficient [-]: k_r = alpha_r k_s R1 R2
  double eta_r = -1.0;        ///< rolling strength coefficient [-]; < 0: no cap
  double alpha_t = 0.0;       ///< twisting stiffness coefficient [-]: k_t = alpha_t k_s R1 R2
  double eta_t = -1.0;        ///< twisting strength coefficient [-]; < 0: no cap

  /// Throws common::InputError naming the first invalid entry.
  void validate() const;
};

/// Numerical parameters of the integrator and neighbour search.
struct Numerics {
  double damping = 0.2;           ///< Cundall non-viscous damping lambda [-], in [0, 1)
  double dt_safety = 0.8;         ///< safety factor on the global-stiffness critical step [-]
  double skin_factor = 0.15;      ///< Verlet skin as a fraction of the largest radius [-]
  std::int64_t dt_refresh = 100;  ///< steps between critical time step refreshes [-]
  double max_skew = 0.5;          ///< re-map the cell when |c_b . c_a| / |c_a|^2 exceeds this [-]

  void validate() const;
};

}  // namespace dem
