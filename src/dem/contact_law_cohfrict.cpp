// CohFrictLaw: YADE's CohFrictPhys creation and CohesionMoment incremental law (no cohesion).
#include "dem/contact_law_cohfrict.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace dem {

using common::Vec3;

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

namespace {
// Radial return of a tangential vector onto the disc of radius cap.
inline void radial_return(Vec3& v, double cap) {
  const double n2 = v.squaredNorm();
  if (n2 > cap * cap) {
    v *= cap / std::sqrt(n2);
  }
}
}  // namespace

void CohFrictLaw::apply(const CohFrictProps& p, CohFrictHistory& h, const ContactKinematics& k,
                        bool is_new, double dt, ContactResult& out) const {
  const double l = k.d.norm();
  const Vec3 n = k.d / l;
  const double delta = k.r1 + k.r2 - l;
  if (is_new) {
    h.shear.setZero();
    h.roll.setZero();
    h.twist.setZero();
  } else {
    // Carry the tangential vectors with the contact frame (ScGeom::precompute / rotate).
    const Vec3 orth = h.normal.cross(n);
    const Vec3 twist_axis = (dt * 0.5 * h.normal.dot(k.w1 + k.w2)) * h.normal;
    h.shear -= h.shear.cross(orth);
    h.shear -= h.shear.cross(twist_axis);
    h.roll -= h.roll.cross(orth);
    h.roll -= h.roll.cross(twist_axis);
    h.twist -= h.twist.cross(orth);
    h.twist -= h.twist.cross(twist_axis);
  }
  h.normal = n;

  // Relative velocity at the contact, YADE's ratcheting-avoiding form.
  const double a = (k.r1 + k.r2) / (k.r1 + k.r2 - delta);
  const Vec3 vrel = a * k.dv + k.w2.cross(-k.r2 * n) - k.w1.cross(k.r1 * n);
  const Vec3 dus = dt * (vrel - n.dot(vrel) * n);

  const double fn = p.kn * delta;
  h.shear -= p.ks * dus;
  radial_return(h.shear, fn * p.tan_phi);

  const Vec3 f = fn * n + h.shear;
  out.force = f;
  out.fn = fn;
  // Torques of F applied at c = x1 + (R1 - delta/2) n: (c - x1) x (-F) and (c - x2) x F.
  const Vec3 nxf = n.cross(h.shear);
  out.torque1 = -(k.r1 - 0.5 * delta) * nxf;
  out.torque2 = -(k.r2 - 0.5 * delta) * nxf;

  // Rolling and twisting moments, incremental, elastic-plastic.
  if (p.kr != 0.0 || p.kt != 0.0) {
    const Vec3 wrel = k.w2 - k.w1;
    const double wn = n.dot(wrel);
    if (p.kr != 0.0) {
      h.roll -= (p.kr * dt) * (wrel - wn * n);
      if (p.roll_cap >= 0.0) radial_return(h.roll, p.roll_cap * fn);
    }
    if (p.kt != 0.0) {
      h.twist -= (p.kt * dt * wn) * n;
      if (p.twist_cap >= 0.0) radial_return(h.twist, p.twist_cap * fn);
    }
    const Vec3 m = h.roll + h.twist;
    out.torque1 -= m;
    out.torque2 += m;
  }
}

}  // namespace dem
