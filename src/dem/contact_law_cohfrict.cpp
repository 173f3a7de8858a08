// CohFrictLaw: YADE's CohFrictPhys creation and CohesionMoment incremental law (no cohesion).
#include "dem/contact_law_cohfrict.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace dem {

CohFrictLaw::CohFrictLaw(const Material& mat) : mat_(mat) { set_friction_deg(mat.friction_deg); }

void CohFrictLaw::set_friction_deg(double phi_deg) {
  mat_.friction_deg = phi_deg;
  tan_phi_ = std::tan(phi_deg * std::numbers::pi / 180.0);
}

CohFrictProps CohFrictLaw::create(double r1, double r2) const {
  CohFrictProps p;
  // Harmonic forms of YADE's Ip2_CohFrictMat_CohFrictMat_CohFrictPhys, identical materials.
  const double ea = mat_.young * r1;
  const double eb = mat_.young * r2;
  p.kn = 2.0 * ea * eb / (ea + eb);
  const double sa = ea * mat_.ks_over_kn;
  const double sb = eb * mat_.ks_over_kn;
  p.ks = (sa + sb) > 0.0 ? 2.0 * sa * sb / (sa + sb) : 0.0;
  p.kr = mat_.alpha_r * p.ks * r1 * r2;
  p.kt = mat_.alpha_t * p.ks * r1 * r2;
  p.tan_phi = tan_phi_;
  const double rmin = std::min(r1, r2);
  p.roll_cap = mat_.eta_r >= 0.0 ? mat_.eta_r * rmin : -1.0;
  p.twist_cap = mat_.eta_t >= 0.0 ? mat_.eta_t * rmin : -1.0;
  return p;
}

}  // namespace dem
