// The reference material of the project (the paper's Table 1 as YADE runs it; docs/design/dem.md
// gives the sources): the one home of its parameters for tests, benchmarks and tools. Jobs carry
// their own copy in TOML, as users do.
#pragma once

#include "dem/params.hpp"

namespace dem {

/// Quartz-like spheres with rolling resistance: rho 2650 kg/m^3, E 300 MPa, k_s/k_n 0.5,
/// friction 30 deg, alpha_r 2, eta_r 0.3, no twisting resistance.
inline Material reference_material() {
  Material m;
  m.density = 2650.0;
  m.young = 3e8;
  m.ks_over_kn = 0.5;
  m.friction_deg = 30.0;
  m.alpha_r = 2.0;
  m.eta_r = 0.3;
  m.alpha_t = 0.0;
  m.eta_t = -1.0;
  return m;
}

/// The Hertz-Mindlin material of the YADE comparisons (jobs/triaxial_dem_hertz_mindlin.toml,
/// tools/mpmxdem_tools/references/yade_triax_hertz_mindlin.py): rho 2650 kg/m^3, grains' E 3 GPa,
/// nu 0.25, friction 30 deg, kr 1e-4 N m/rad, eta 0.3, no twisting.
inline Material hertz_mindlin_reference_material() {
  Material m;
  m.law = ContactLawKind::hertz_mindlin;
  m.density = 2650.0;
  m.young = 3e9;
  m.friction_deg = 30.0;
  m.hm.poisson = 0.25;
  m.hm.krot = 1e-4;
  m.hm.ktwist = 0.0;
  m.hm.eta = 0.3;
  return m;
}

}  // namespace dem
