// Linear elastic-frictional contact with elastic-plastic rolling and twisting resistance, as YADE's
// Law2_ScGeom6D_CohFrictPhys_CohesionMoment (incremental form, no cohesion). Aboul Hosn et al.
// 2017, Granular Matter 19(1); see docs/design/dem.md and docs/validation/yade_reference.md sections 1-3.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/types.hpp"
#include "dem/cohfrict_arrays.hpp"
#include "dem/params.hpp"

namespace dem {

/// Kinematics of one contact this step (what the law sees of the two spheres).
struct ContactKinematics {
  common::Vec3 d;       ///< branch x2 + H k - x1 [m]
  common::Vec3 dv;      ///< relative translational velocity v2 + L s - v1 = u2 - u1 + L d [m/s]
  common::Vec3 w1, w2;  ///< spins [rad/s]
  double r1, r2;        ///< radii [m]
};

/// What the law gives back: force on sphere 2 at the contact point and the torques.
struct ContactResult {
  common::Vec3 force;    ///< total force on sphere 2 (sphere 1 gets the opposite) [N]
  common::Vec3 torque1;  ///< torque on sphere 1 [N m]
  common::Vec3 torque2;  ///< torque on sphere 2 [N m]
  double fn = 0.0;       ///< normal force magnitude [N]
};

/// A run of up to kLanes consecutive Verlet pairs, first .. first + n - 1, for the batched
/// (vectorised) form of the law. The force loop fills the kinematics of every lane (pairs in
/// overlap or not), CohFrictLaw::apply_batch computes all lanes at once, reading and writing the
/// properties and history of pair first + q in the contacts' arrays in place, and the force loop
/// reads the outputs back. Lane q of every array is pair first + q.
struct CohFrictBatch {
  static constexpr int kLanes = 64;
  int n = 0;              ///< lanes in use
  std::size_t first = 0;  ///< pair of lane 0
  // Inputs (per pair): branch d, |d|^2, u2 - u1, spins, radii.
  alignas(64) double d[3][kLanes];   ///< branch x2 + H k - x1 [m]
  alignas(64) double l2[kLanes];     ///< |d|^2 [m^2]
  alignas(64) double du[3][kLanes];  ///< fluctuating velocity difference u2 - u1 [m/s]
  alignas(64) double w1[3][kLanes], w2[3][kLanes];  ///< spins [rad/s]
  alignas(64) double r1[kLanes], r2[kLanes];        ///< radii [m]
  /// 1: the spheres overlap (a contact this step), 0: they do not (outputs +0, history and
  /// properties untouched).
  alignas(64) std::int64_t touching[kLanes];
  /// 1: the contact is created this step (its history is taken as zero; its properties must be
  /// in the arrays already).
  alignas(64) std::int64_t fresh[kLanes];
  // Outputs (+0 for lanes not touching).
  alignas(64) double force[3][kLanes];    ///< force on sphere 2 [N]
  alignas(64) double torque1[3][kLanes];  ///< [N m]
  alignas(64) double torque2[3][kLanes];  ///< [N m]
  // The normal force magnitude is kn ((r1 + r2) - sqrt(l2)) (Simulation::normal_force).
};

/// The stiffnesses and moment caps of a contact between radii r1 and r2 [m] of material m:
/// every property but the friction coefficient. Harmonic forms of YADE's
/// Ip2_CohFrictMat_CohFrictMat_CohFrictPhys for identical materials. They are computed where they
/// are needed (the batched law computes them lane by lane) instead of stored per pair: a step then
/// reads 48 bytes less per pair (docs/design/dem.md "Speed"). One definition, so that every use has the
/// same bits.
struct CohFrictStiffness {
  double kn, ks, kr, kt, roll_cap, twist_cap;
};
[[gnu::always_inline]] inline CohFrictStiffness cohfrict_stiffness(const Material& m, double r1,
                                                                   double r2) {
  const double ea = m.young * r1;
  const double eb = m.young * r2;
  const double kn = 2.0 * ea * eb / (ea + eb);
  const double sa = ea * m.ks_over_kn;
  const double sb = eb * m.ks_over_kn;
  const double ks = (sa + sb) > 0.0 ? 2.0 * sa * sb / (sa + sb) : 0.0;
  const double rmin = r2 < r1 ? r2 : r1;  // std::min(r1, r2)
  return {kn,
          ks,
          m.alpha_r * ks * r1 * r2,
          m.alpha_t * ks * r1 * r2,
          m.eta_r >= 0.0 ? m.eta_r * rmin : -1.0,
          m.eta_t >= 0.0 ? m.eta_t * rmin : -1.0};
}

/// The contact law functor. Stateless apart from the material; all history lives in the contact.
class CohFrictLaw {
 public:
  explicit CohFrictLaw(const Material& mat);

  /// Properties of a new contact between radii r1, r2 [m] (the current friction angle).
  [[nodiscard]] ContactProps create(double r1, double r2) const { return props(r1, r2, tan_phi_); }
  /// Properties of a contact between radii r1, r2 [m] created with friction coefficient tan_phi.
  [[nodiscard]] ContactProps props(double r1, double r2, double tan_phi) const {
    const CohFrictStiffness k = cohfrict_stiffness(mat_, r1, r2);
    return {k.kn, k.ks, k.kr, k.kt, tan_phi, k.roll_cap, k.twist_cap};
  }
  /// Friction coefficient of a contact created now: tan of the current friction angle.
  [[nodiscard]] double tan_phi() const { return tan_phi_; }
  /// Whether contacts may have twisting stiffness (kt = alpha_t ks R1 R2 is zero when not).
  [[nodiscard]] bool twists() const { return mat_.alpha_t != 0.0; }

  /// One step of the law for a contact in overlap (delta = r1 + r2 - |d| > 0).
  /// @param is_new  true on the step the contact is created (history is reset, no rotation)
  /// @param dt      time step [s]
  void apply(const ContactProps& props, CohFrictHistory& hist, const ContactKinematics& kin,
             bool is_new, double dt, ContactResult& out) const;

  /// The same law for the b.n lanes of a batch, lane by lane the same floating-point operations
  /// in the same order as apply() (bit-identical results, tested), in vectorisable loops; the
  /// relative velocity is u2 - u1 + L d with the cell's velocity gradient l [1/s]. Lane q reads
  /// tan_phi and reads and writes hist at pair b.first + q, and computes the other properties
  /// from its radii (props(r1, r2, tan_phi)); a lane not touching leaves its history as it was and
  /// gives zero force and torques. twist_possible = false: no pair has a twisting moment and
  /// twists() is false (the twisting part is skipped without looking).
  void apply_batch(CohFrictBatch& b, const std::vector<double>& tan_phi,
                   CohFrictHistoryArrays& hist, const common::Mat3& l, double dt,
                   bool twist_possible = true) const;

  [[nodiscard]] const Material& material() const { return mat_; }
  /// Change the friction angle used for new contacts [deg].
  void set_friction_deg(double phi_deg);

 private:
  Material mat_;
  double tan_phi_ = 0.0;
};

/// Lanes of the critical time step's stiffness sums (Simulation::critical_dt): up to kLanes pairs
/// with radii r1, r2 and stored normal n (components n0, n1, n2); out, per lane, the translational
/// terms kt_a = ks + (kn - ks) n_a^2 (the same for both spheres) and the rotational terms of each
/// sphere, kr_a = ks r^2 (1 - n_a^2) + (kt - kr) n_a^2 + kr with its own radius r (r1: kr1, r2:
/// kr2), the stiffnesses of cohfrict_stiffness: the operations of the scalar form, bit for bit.
struct StiffnessLanes {
  static constexpr int kLanes = 64;
  int n = 0;
  alignas(64) double r1[kLanes], r2[kLanes], n0[kLanes], n1[kLanes], n2[kLanes];
  /// Overlap r1 + r2 - |d| [m]: read only by laws whose stiffness depends on it (Hertz-Mindlin).
  alignas(64) double delta[kLanes];
  alignas(64) double kt[3][kLanes], kr1[3][kLanes], kr2[3][kLanes];
};
void stiffness_lanes(const Material& m, StiffnessLanes& b);

// Defined inline: it is the body of the force loop.
namespace detail {
/// Radial return of a tangential vector onto the disc of radius cap.
inline void radial_return(common::Vec3& v, double cap) {
  const double n2 = v.squaredNorm();
  if (n2 > cap * cap) {
    v *= cap / std::sqrt(n2);
  }
}
}  // namespace detail

inline void CohFrictLaw::apply(const ContactProps& p, CohFrictHistory& h,
                               const ContactKinematics& k, bool is_new, double dt,
                               ContactResult& out) const {
  const double l = k.d.norm();
  const common::Vec3 n = k.d / l;
  const double delta = k.r1 + k.r2 - l;
  if (is_new) {
    h.shear.setZero();
    h.roll.setZero();
    h.twist.setZero();
  } else {
    // Carry the tangential vectors with the contact frame (ScGeom::precompute / rotate).
    const common::Vec3 orth = h.normal.cross(n);
    const common::Vec3 twist_axis = (dt * 0.5 * h.normal.dot(k.w1 + k.w2)) * h.normal;
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
  const common::Vec3 vrel = a * k.dv + k.w2.cross(-k.r2 * n) - k.w1.cross(k.r1 * n);
  const common::Vec3 dus = dt * (vrel - n.dot(vrel) * n);

  const double fn = p.kn * delta;
  h.shear -= p.ks * dus;
  detail::radial_return(h.shear, fn * p.tan_phi);

  const common::Vec3 f = fn * n + h.shear;
  out.force = f;
  out.fn = fn;
  // Torques of F applied at c = x1 + (R1 - delta/2) n: (c - x1) x (-F) and (c - x2) x F.
  const common::Vec3 nxf = n.cross(h.shear);
  out.torque1 = -(k.r1 - 0.5 * delta) * nxf;
  out.torque2 = -(k.r2 - 0.5 * delta) * nxf;

  // Rolling and twisting moments, incremental, elastic-plastic.
  if (p.kr != 0.0 || p.kt != 0.0) {
    const common::Vec3 wrel = k.w2 - k.w1;
    const double wn = n.dot(wrel);
    if (p.kr != 0.0) {
      h.roll -= (p.kr * dt) * (wrel - wn * n);
      if (p.roll_cap >= 0.0) detail::radial_return(h.roll, p.roll_cap * fn);
    }
    if (p.kt != 0.0) {
      h.twist -= (p.kt * dt * wn) * n;
      if (p.twist_cap >= 0.0) detail::radial_return(h.twist, p.twist_cap * fn);
    }
    const common::Vec3 m = h.roll + h.twist;
    out.torque1 -= m;
    out.torque2 += m;
  }
}

}  // namespace dem
