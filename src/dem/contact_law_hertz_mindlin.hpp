// Hertz-Mindlin contact with rolling and twisting moments, as YADE 2023.02a computes it:
// Ip2_FrictMat_FrictMat_MindlinPhys (the coefficients) and Law2_ScGeom_MindlinPhys_Mindlin::go with
// includeMoment = true, without damping or adhesion (pkg/dem/HertzMindlin.cpp). Per contact and
// step, with the overlap delta and the normal n of the geometry (section 1 of
// docs/validation/yade_reference.md, as for the CohFrict law):
//   Fn = kno delta^1.5 (computed as delta sqrt(delta)), tangent ks = kso sqrt(delta);
//   the shear force, bending and twisting moments are carried with the contact frame (ScGeom::
//   rotate), then Fs -= ks du_s (the ratcheting-free shear increment), |Fs| <= Fn tan phi;
//   Mb -= kr dt w_b, Mt -= kt dt w_t (w_b, w_t: bending and twisting parts of w2 - w1), and
//   |Mb| <= eta (R1 + R2)/2 Fn when eta > 0 (the twisting moment has no cap);
//   sphere 2 gets F = Fn n + Fs at the contact point and + (Mb + Mt), sphere 1 the opposite.
// The history is that of the CohFrict law (normal, shear force, bending = roll, twist): the same
// arrays, checkpoint fields and measures.
#pragma once

#include <cmath>
#include <vector>

#include "common/types.hpp"
#include "dem/cohfrict_arrays.hpp"
#include "dem/contact_law_cohfrict.hpp"
#include "dem/params.hpp"

namespace dem {

/// The material's factors of the pair coefficients: 4/3 E* [Pa] and G / (2 - nu) [Pa], with
/// E* = E E / ((1 - nu^2) E + (1 - nu^2) E) and G = (Ga + Gb) / 2 as YADE forms them for one
/// material, and eta.
struct HertzMindlinConstants {
  double kn_factor, ks_factor, eta;
};
[[gnu::always_inline]] inline HertzMindlinConstants hertz_mindlin_constants(const Material& m) {
  const double e = m.young;
  const double nu = m.hm.poisson;
  const double g = e / (2.0 * (1.0 + nu));
  const double e_star = e * e / ((1.0 - nu * nu) * e + (1.0 - nu * nu) * e);
  return {4.0 / 3.0 * e_star, ((g + g) / 2.0) / (2.0 - nu), m.hm.eta};
}

/// The coefficients of a pair of radii r1, r2 [m] (Ip2_FrictMat_FrictMat_MindlinPhys for one
/// material): kno = 4/3 E* sqrt(R*) [N/m^1.5], kso = 2 sqrt(4 R*) G / (2 - nu) [N/m^1.5] (as
/// 4 sqrt(R*) times G / (2 - nu): sqrt(4 x) is 2 sqrt(x) exactly), the bending cap
/// eta (R1 + R2)/2 [m] (< 0: no cap). One definition for the force loop, the time step and the
/// measures: the same bits everywhere.
struct HertzMindlinCoefficients {
  double kno, kso, roll_cap;
};
[[gnu::always_inline]] inline HertzMindlinCoefficients hertz_mindlin_coefficients(
    const HertzMindlinConstants& c, double r1, double r2) {
  const double root = std::sqrt(r1 * r2 / (r1 + r2));
  const double cap = c.eta * ((r1 + r2) / 2.0);
  return {c.kn_factor * root, (4.0 * root) * c.ks_factor, cap > 0.0 ? cap : -1.0};
}
[[gnu::always_inline]] inline HertzMindlinCoefficients hertz_mindlin_coefficients(
    const Material& m, double r1, double r2) {
  return hertz_mindlin_coefficients(hertz_mindlin_constants(m), r1, r2);
}

/// The Hertz-Mindlin law: stateless apart from the material; the history lives in the contacts.
class HertzMindlinLaw {
 public:
  explicit HertzMindlinLaw(const Material& mat) : mat_(mat), c_(hertz_mindlin_constants(mat)) {}

  /// Normal force kno delta^1.5 of radii r1, r2 [m] at overlap delta > 0 [m], the law's bits.
  [[nodiscard]] double normal_force(double r1, double r2, double delta) const {
    return hertz_mindlin_coefficients(c_, r1, r2).kno * (delta * std::sqrt(delta));
  }
  /// The tangent stiffnesses at overlap delta [m] (kn = 3/2 kno sqrt(delta), ks = kso
  /// sqrt(delta): what YADE's MindlinPhys stores for its time stepper), kr, kt, the caps.
  [[nodiscard]] ContactProps props(double r1, double r2, double delta, double tan_phi) const;
  /// Whether contacts may twist (a twisting stiffness).
  [[nodiscard]] bool twists() const { return mat_.hm.ktwist != 0.0; }

  /// The law for the b.n lanes of a batch (CohFrictLaw::apply_batch's contract: lane q reads
  /// tan_phi and reads and writes hist at pair b.first + q; a lane not touching keeps its
  /// history and gives zero force and torques). twist_possible = false: no pair has a twisting
  /// moment and twists() is false.
  void apply_batch(CohFrictBatch& b, const std::vector<double>& tan_phi,
                   CohFrictHistoryArrays& hist, const common::Mat3& l, double dt,
                   bool twist_possible = true) const;

  /// Lanes of the critical time step's stiffness sums (stiffness_lanes) with the tangent
  /// stiffnesses at each lane's overlap `delta` (read from b.delta).
  void stiffness_lanes(StiffnessLanes& b) const;

 private:
  Material mat_;
  HertzMindlinConstants c_;
};

}  // namespace dem
