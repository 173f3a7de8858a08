// HertzMindlinLaw: YADE's Law2_ScGeom_MindlinPhys_Mindlin (moments on, no damping, no adhesion)
// in the batched form of the force loop (see the header).
#include "dem/contact_law_hertz_mindlin.hpp"

#include <cmath>

#include "dem/lane_math.hpp"

namespace dem {

ContactProps HertzMindlinLaw::props(double r1, double r2, double delta, double tan_phi) const {
  const HertzMindlinCoefficients k = hertz_mindlin_coefficients(c_, r1, r2);
  const double root = delta > 0.0 ? std::sqrt(delta) : 0.0;
  return {3.0 / 2.0 * k.kno * root, k.kso * root, mat_.hm.krot, mat_.hm.ktwist, tan_phi,
          k.roll_cap, -1.0};
}

namespace {

using namespace lane;

template <bool kTwist>
[[gnu::always_inline]] inline void apply_lanes(CohFrictBatch& b, const Material& material,
                                               const HertzMindlinConstants& constants,
                                               const double* tan_phi_all, CohFrictHistoryArrays& ha,
                                               const common::Mat3& lm, double dt) {
  const Gradient g = gradient_of(lm);
  // Local copies: the history stores cannot alias them.
  const double kr = material.hm.krot;
  const double kt = material.hm.ktwist;
  const HertzMindlinConstants c = constants;
  const double* const tan_phi = tan_phi_all + b.first;
  const Vec3At hn(ha.normal, b.first);
  const Vec3At hs(ha.shear, b.first);
  const Vec3At hr(ha.roll, b.first);
  const Vec3At ht(ha.twist, b.first);
  const V3 zero{0.0, 0.0, 0.0};
  const int nl = b.n;
#pragma omp simd
  for (int q = 0; q < nl; ++q) {
    const bool touch = b.touching[q] != 0;
    const bool fresh = b.fresh[q] != 0;
    const V3 d = load(b.d, q);
    const double len = std::sqrt(b.l2[q]);
    const V3 n{d.x / len, d.y / len, d.z / len};
    const double r1 = b.r1[q];
    const double r2 = b.r2[q];
    // Lanes out of overlap compute with delta = 0 (no NaN from a negative root); their outputs
    // are +0 and their history is kept.
    const double delta = touch ? (r1 + r2) - len : 0.0;
    const HertzMindlinCoefficients k = hertz_mindlin_coefficients(c, r1, r2);
    const double root = std::sqrt(delta);
    const V3 w1 = load(b.w1, q);
    const V3 w2 = load(b.w2, q);

    // Carry the tangential vectors with the contact frame (a new contact: zero history).
    const V3 h = select(fresh, zero, hn.load(q));
    const FrameMotion fm = frame_motion(h, n, w1, w2, dt);
    const V3& orth = fm.orth;
    const V3& twist_axis = fm.twist_axis;
    V3 shear = carry(select(fresh, zero, hs.load(q)), orth, twist_axis);
    V3 roll = carry(select(fresh, zero, hr.load(q)), orth, twist_axis);
    hn.store_if(touch, q, n);

    // The shear increment from the relative velocity at the contact.
    const V3 dus = shear_increment(d, n, load(b.du, q), w1, w2, r1, r2, delta, g, dt);

    const double fn = k.kno * (delta * root);
    const double ks = k.kso * root;
    shear = sub(shear, scale(ks, dus));
    shear = radial_return(shear, fn * tan_phi[q]);
    hs.store_if(touch, q, shear);
    store(b.force, q,
          select(touch, V3{fn * n.x + shear.x, fn * n.y + shear.y, fn * n.z + shear.z}, 0.0));
    const V3 nxf = cross(n, shear);
    V3 t1 = scale(-(r1 - 0.5 * delta), nxf);
    V3 t2 = scale(-(r2 - 0.5 * delta), nxf);

    // Bending (capped when eta > 0) and twisting (never capped) moments.
    const V3 wrel = sub(w2, w1);
    const double wn = dot(n, wrel);
    const V3 roll_el =
        sub(roll, scale(kr * dt, {wrel.x - wn * n.x, wrel.y - wn * n.y, wrel.z - wn * n.z}));
    roll = select(k.roll_cap >= 0.0, radial_return(roll_el, k.roll_cap * fn), roll_el);
    hr.store_if(touch, q, roll);
    V3 m;
    if constexpr (kTwist) {
      V3 twist = carry(select(fresh, zero, ht.load(q)), orth, twist_axis);
      twist = sub(twist, scale(kt * dt * wn, n));
      ht.store_if(touch, q, twist);
      m = {roll.x + twist.x, roll.y + twist.y, roll.z + twist.z};
    } else {
      m = {roll.x + 0.0, roll.y + 0.0, roll.z + 0.0};
    }
    t1 = sub(t1, m);
    t2 = V3{t2.x + m.x, t2.y + m.y, t2.z + m.z};
    store(b.torque1, q, select(touch, t1, 0.0));
    store(b.torque2, q, select(touch, t2, 0.0));
  }
}


// One clone per instruction set, as the CohFrict law's (contact_law_cohfrict.cpp): the same
// operations, 2, 4 or 8 lanes at a time, no fused multiply-add (-ffp-contract=off on this file).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define MPMXDEM_LANE_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define MPMXDEM_LANE_CLONES
#endif
MPMXDEM_LANE_CLONES void run_lanes(CohFrictBatch& b, const Material& mat,
                                   const HertzMindlinConstants& c, const double* tan_phi,
                                   CohFrictHistoryArrays& ha, const common::Mat3& l, double dt,
                                   bool twist_possible) {
  if (twist_possible && (mat.hm.ktwist != 0.0 || twist_on(ha, b.first, b.n))) {
    apply_lanes<true>(b, mat, c, tan_phi, ha, l, dt);
  } else {
    apply_lanes<false>(b, mat, c, tan_phi, ha, l, dt);
  }
}
#undef MPMXDEM_LANE_CLONES

}  // namespace

void HertzMindlinLaw::apply_batch(CohFrictBatch& b, const std::vector<double>& tan_phi,
                                  CohFrictHistoryArrays& hist, const common::Mat3& l, double dt,
                                  bool twist_possible) const {
  run_lanes(b, mat_, c_, tan_phi.data(), hist, l, dt, twist_possible);
}

void HertzMindlinLaw::stiffness_lanes(StiffnessLanes& b) const {
  const int nl = b.n;
  for (int q = 0; q < nl; ++q) {
    const double r1 = b.r1[q];
    const double r2 = b.r2[q];
    const ContactProps k = props(r1, r2, b.delta[q], 0.0);
    const double a0 = b.n0[q] * b.n0[q];
    const double a1 = b.n1[q] * b.n1[q];
    const double a2 = b.n2[q] * b.n2[q];
    const double dn = k.kn - k.ks;
    const double dk = k.kt - k.kr;
    const double s1 = k.ks * r1 * r1;
    const double s2 = k.ks * r2 * r2;
    b.kt[0][q] = k.ks + dn * a0;
    b.kt[1][q] = k.ks + dn * a1;
    b.kt[2][q] = k.ks + dn * a2;
    b.kr1[0][q] = s1 * (1.0 - a0) + dk * a0 + k.kr;
    b.kr1[1][q] = s1 * (1.0 - a1) + dk * a1 + k.kr;
    b.kr1[2][q] = s1 * (1.0 - a2) + dk * a2 + k.kr;
    b.kr2[0][q] = s2 * (1.0 - a0) + dk * a0 + k.kr;
    b.kr2[1][q] = s2 * (1.0 - a1) + dk * a1 + k.kr;
    b.kr2[2][q] = s2 * (1.0 - a2) + dk * a2 + k.kr;
  }
}

}  // namespace dem
