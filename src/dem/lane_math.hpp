// Per-lane 3-vector arithmetic of the batched contact laws (dem/contact_law_*.cpp), written out
// as Eigen evaluates it for 3-vectors, operation for operation, so that a lane gives the bits of
// the Eigen form: dot products and squared norms sum (x0 y0 + x1 y1) + x2 y2, cross products are
// (a1 b2 - a2 b1, a2 b0 - a0 b2, a0 b1 - a1 b0). Branches become selects (both sides computed,
// one kept), which the vectoriser turns into blends.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "dem/cohfrict_arrays.hpp"

namespace dem::lane {

struct V3 {
  double x, y, z;
};

inline V3 cross(const V3& a, const V3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double dot(const V3& a, const V3& b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
inline V3 sub(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 scale(double s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }

// v <- v - v x orth, then v <- v - v x twist_axis (ScGeom::precompute / rotate).
inline V3 carry(const V3& v, const V3& orth, const V3& twist_axis) {
  const V3 v1 = sub(v, cross(v, orth));
  return sub(v1, cross(v1, twist_axis));
}

// c ? a : b, component by component (a select the vectoriser turns into a blend).
inline V3 select(bool c, const V3& a, const V3& b) {
  return {c ? a.x : b.x, c ? a.y : b.y, c ? a.z : b.z};
}

// detail::radial_return as a select.
inline V3 radial_return(const V3& v, double cap) {
  const double n2 = dot(v, v);
  return select(n2 > cap * cap, scale(cap / std::sqrt(n2), v), v);
}

inline V3 select(bool c, const V3& a, double b) { return {c ? a.x : b, c ? a.y : b, c ? a.z : b}; }

// Lane q of a batch is pair first + q of the contacts' arrays: pointers shifted to the batch's
// first pair.
struct Vec3At {
  double *x, *y, *z;
  Vec3At(std::array<std::vector<double>, 3>& a, std::size_t f)
      : x(a[0].data() + f), y(a[1].data() + f), z(a[2].data() + f) {}
  [[nodiscard]] V3 load(int q) const { return {x[q], y[q], z[q]}; }
  // Lanes not touching keep their value: v where c, else the old one.
  void store_if(bool c, int q, const V3& v) const {
    x[q] = c ? v.x : x[q];
    y[q] = c ? v.y : y[q];
    z[q] = c ? v.z : z[q];
  }
};

template <int N>
inline V3 load(const double (&a)[3][N], int q) {
  return {a[0][q], a[1][q], a[2][q]};
}
template <int N>
inline void store(double (&a)[3][N], int q, const V3& v) {
  a[0][q] = v.x;
  a[1][q] = v.y;
  a[2][q] = v.z;
}

// The velocity gradient of the cell, its nine entries row by row (locals the vectoriser keeps in
// registers).
struct Gradient {
  double l00, l01, l02, l10, l11, l12, l20, l21, l22;
};
template <class M>
inline Gradient gradient_of(const M& l) {
  return {l(0, 0), l(0, 1), l(0, 2), l(1, 0), l(1, 1), l(1, 2), l(2, 0), l(2, 1), l(2, 2)};
}

// The contact frame's motion over the step (ScGeom::precompute): the tangential vectors are
// carried by carry(v, orth, twist_axis) with orth = h x n and twist_axis = dt/2 (h . (w1 + w2)) h,
// h the stored normal of the previous step (zero for a new contact: no rotation).
struct FrameMotion {
  V3 orth, twist_axis;
};
[[gnu::always_inline]] inline FrameMotion frame_motion(const V3& h, const V3& n, const V3& w1,
                                                       const V3& w2, double dt) {
  const V3 ws{w1.x + w2.x, w1.y + w2.y, w1.z + w2.z};
  return {cross(h, n), scale(dt * 0.5 * dot(h, ws), h)};
}

// The shear displacement increment dt (v_rel - (n . v_rel) n) of a contact with branch d, unit
// normal n, overlap delta, fluctuating velocity difference du and spins w1, w2: YADE's
// ratcheting-free relative velocity v_rel = a (du + L d) + w2 x (-r2 n) - w1 x (r1 n),
// a = (r1 + r2) / ((r1 + r2) - delta).
[[gnu::always_inline]] inline V3 shear_increment(const V3& d, const V3& n, const V3& du,
                                                 const V3& w1, const V3& w2, double r1, double r2,
                                                 double delta, const Gradient& g, double dt) {
  const double a = (r1 + r2) / ((r1 + r2) - delta);
  const V3 dv{du.x + ((g.l00 * d.x + g.l01 * d.y) + g.l02 * d.z),
              du.y + ((g.l10 * d.x + g.l11 * d.y) + g.l12 * d.z),
              du.z + (g.l20 * d.x + (g.l21 * d.y + g.l22 * d.z))};
  const V3 c2 = cross(w2, scale(-r2, n));
  const V3 c1 = cross(w1, scale(r1, n));
  const V3 vrel{(a * dv.x + c2.x) - c1.x, (a * dv.y + c2.y) - c1.y, (a * dv.z + c2.z) - c1.z};
  const double nv = dot(n, vrel);
  return {dt * (vrel.x - nv * n.x), dt * (vrel.y - nv * n.y), dt * (vrel.z - nv * n.z)};
}

// Whether one of the n pairs from `first` on has a twisting moment: else (and when the material
// has no twisting stiffness) a law skips its twisting part (the twist of every lane is +0 and
// stays so). Lanes not touching may turn it on: the twisting part then leaves a zero twist +0,
// the same bits.
inline bool twist_on(const CohFrictHistoryArrays& ha, std::size_t first, int n) {
  const double* tx = ha.twist[0].data() + first;
  const double* ty = ha.twist[1].data() + first;
  const double* tz = ha.twist[2].data() + first;
  int on = 0;
#pragma omp simd reduction(| : on)
  for (int q = 0; q < n; ++q) {
    on |= static_cast<int>(tx[q] != 0.0) | static_cast<int>(ty[q] != 0.0) |
          static_cast<int>(tz[q] != 0.0);
  }
  return on != 0;
}

}  // namespace dem::lane
