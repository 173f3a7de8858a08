// CohFrictLaw: YADE's CohFrictPhys creation and CohesionMoment incremental law (no cohesion).
#include "dem/contact_law_cohfrict.hpp"
#include "dem/lane_math.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace dem {

CohFrictLaw::CohFrictLaw(const Material& mat) : mat_(mat) { set_friction_deg(mat.friction_deg); }

void CohFrictLaw::set_friction_deg(double phi_deg) {
  mat_.friction_deg = phi_deg;
  tan_phi_ = std::tan(phi_deg * std::numbers::pi / 180.0);
}

// ---- Batched form. Every expression below is the one apply() evaluates through Eigen, operation
// for operation (no reassociation, no fused multiply-add), so that each lane is bit-identical to
// apply(): Eigen's dot products and squared norms of 3-vectors sum (x0 y0 + x1 y1) + x2 y2, its
// cross products are (a1 b2 - a2 b1, a2 b0 - a0 b2, a0 b1 - a1 b0), and its 3x3 times 3-vector
// product sums rows 0 and 1 as (m0 x0 + m1 x1) + m2 x2 but row 2 as m0 x0 + (m1 x1 + m2 x2).
// Branches of apply() become selects: both sides are computed, one is kept.
namespace {

using namespace lane;  // V3 and its operations: dem/lane_math.hpp

// Long by design (~80 lines): the contact law of one batch of lanes in one always-inlined body,
// the form the vectoriser needs; its steps follow apply() line for line.
template <bool kTwist>
[[gnu::always_inline]] inline void apply_lanes(CohFrictBatch& b, const Material& material,
                                               const double* tan_phi_all, CohFrictHistoryArrays& ha,
                                               const common::Mat3& lm, double dt) {
  const Gradient g = gradient_of(lm);
  // A local copy: the stores to the history arrays cannot alias it (its fields stay in registers).
  const Material mat = material;
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
    // A new contact starts from a zero history (apply() zeroes it and skips the rotation;
    // rotating zero vectors by finite ones gives +0 again, so a zero history is the same).
    const bool fresh = b.fresh[q] != 0;
    const V3 d = load(b.d, q);
    const double len = std::sqrt(b.l2[q]);
    const V3 n{d.x / len, d.y / len, d.z / len};
    const double r1 = b.r1[q];
    const double r2 = b.r2[q];
    const double delta = (r1 + r2) - len;
    const CohFrictStiffness k = cohfrict_stiffness(mat, r1, r2);
    const V3 w1 = load(b.w1, q);
    const V3 w2 = load(b.w2, q);

    // Carry the tangential vectors with the contact frame.
    const V3 h = select(fresh, zero, hn.load(q));
    const FrameMotion fm = frame_motion(h, n, w1, w2, dt);
    const V3& orth = fm.orth;
    const V3& twist_axis = fm.twist_axis;
    V3 shear = carry(select(fresh, zero, hs.load(q)), orth, twist_axis);
    V3 roll = carry(select(fresh, zero, hr.load(q)), orth, twist_axis);
    hn.store_if(touch, q, n);

    // The shear increment from the relative velocity at the contact.
    const V3 dus = shear_increment(d, n, load(b.du, q), w1, w2, r1, r2, delta, g, dt);

    const double fn = k.kn * delta;
    shear = sub(shear, scale(k.ks, dus));
    shear = radial_return(shear, fn * tan_phi[q]);
    hs.store_if(touch, q, shear);
    store(b.force, q,
          select(touch, V3{fn * n.x + shear.x, fn * n.y + shear.y, fn * n.z + shear.z}, 0.0));
    const V3 nxf = cross(n, shear);
    V3 t1 = scale(-(r1 - 0.5 * delta), nxf);
    V3 t2 = scale(-(r2 - 0.5 * delta), nxf);

    // Rolling and twisting moments.
    const double kr = k.kr;
    const double kt = k.kt;
    const V3 wrel = sub(w2, w1);
    const double wn = dot(n, wrel);
    const V3 roll_el =
        sub(roll, scale(kr * dt, {wrel.x - wn * n.x, wrel.y - wn * n.y, wrel.z - wn * n.z}));
    const V3 roll_pl = radial_return(roll_el, k.roll_cap * fn);
    roll = select(kr != 0.0, select(k.roll_cap >= 0.0, roll_pl, roll_el), roll);
    hr.store_if(touch, q, roll);
    V3 m;
    if constexpr (kTwist) {
      V3 twist = carry(select(fresh, zero, ht.load(q)), orth, twist_axis);
      const V3 twist_el = sub(twist, scale(kt * dt * wn, n));
      const V3 twist_pl = radial_return(twist_el, k.twist_cap * fn);
      twist = select(kt != 0.0, select(k.twist_cap >= 0.0, twist_pl, twist_el), twist);
      ht.store_if(touch, q, twist);
      m = {roll.x + twist.x, roll.y + twist.y, roll.z + twist.z};
    } else {
      // The twist is +0 and stays so (rotating +0 gives +0): roll + twist is roll + 0.
      m = {roll.x + 0.0, roll.y + 0.0, roll.z + 0.0};
    }
    const bool moments = kr != 0.0 || kt != 0.0;
    t1 = select(moments, sub(t1, m), t1);
    t2 = select(moments, V3{t2.x + m.x, t2.y + m.y, t2.z + m.z}, t2);
    store(b.torque1, q, select(touch, t1, 0.0));
    store(b.torque2, q, select(touch, t2, 0.0));
  }
}

// One clone per instruction set, chosen once at load time by the processor (GCC function
// multi-versioning): the same operations, 2, 4 or 8 lanes at a time. Lanes are independent and
// IEEE operations are exact per lane, and no clone may fuse a multiply and an add
// (-ffp-contract=off on this file; AVX-512 would otherwise allow it), so every clone gives the
// bits of apply().
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define MPMXDEM_LANE_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define MPMXDEM_LANE_CLONES
#endif
MPMXDEM_LANE_CLONES void run_lanes(CohFrictBatch& b, const Material& mat, const double* tan_phi,
                                   CohFrictHistoryArrays& ha, const common::Mat3& l, double dt,
                                   bool twist_possible) {
  // kt = alpha_t ks R1 R2 is +0 for every lane when alpha_t = 0.
  if (twist_possible && (mat.alpha_t != 0.0 || twist_on(ha, b.first, b.n))) {
    apply_lanes<true>(b, mat, tan_phi, ha, l, dt);
  } else {
    apply_lanes<false>(b, mat, tan_phi, ha, l, dt);
  }
}
MPMXDEM_LANE_CLONES void run_stiffness_lanes(const Material& material, StiffnessLanes& b) {
  const Material m = material;  // in registers: the stores below cannot alias it
  const int nl = b.n;
#pragma omp simd
  for (int q = 0; q < nl; ++q) {
    const double r1 = b.r1[q];
    const double r2 = b.r2[q];
    const CohFrictStiffness k = cohfrict_stiffness(m, r1, r2);
    const double a0 = b.n0[q] * b.n0[q];
    const double a1 = b.n1[q] * b.n1[q];
    const double a2 = b.n2[q] * b.n2[q];
    const double dn = k.kn - k.ks;
    const double dt = k.kt - k.kr;
    const double s1 = k.ks * r1 * r1;
    const double s2 = k.ks * r2 * r2;
    b.kt[0][q] = k.ks + dn * a0;
    b.kt[1][q] = k.ks + dn * a1;
    b.kt[2][q] = k.ks + dn * a2;
    b.kr1[0][q] = s1 * (1.0 - a0) + dt * a0 + k.kr;
    b.kr1[1][q] = s1 * (1.0 - a1) + dt * a1 + k.kr;
    b.kr1[2][q] = s1 * (1.0 - a2) + dt * a2 + k.kr;
    b.kr2[0][q] = s2 * (1.0 - a0) + dt * a0 + k.kr;
    b.kr2[1][q] = s2 * (1.0 - a1) + dt * a1 + k.kr;
    b.kr2[2][q] = s2 * (1.0 - a2) + dt * a2 + k.kr;
  }
}
#undef MPMXDEM_LANE_CLONES

}  // namespace

void stiffness_lanes(const Material& m, StiffnessLanes& b) { run_stiffness_lanes(m, b); }

void CohFrictLaw::apply_batch(CohFrictBatch& b, const std::vector<double>& tan_phi,
                              CohFrictHistoryArrays& hist, const common::Mat3& l, double dt,
                              bool twist_possible) const {
  run_lanes(b, mat_, tan_phi.data(), hist, l, dt, twist_possible);
}

}  // namespace dem
