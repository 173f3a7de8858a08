// Tensor helpers shared by every module: the row-major 9-double form of a Mat3 (wire, HDF5,
// checkpoints), the stress invariants p and q, Lamé constants, and the Hughes-Winget objective
// update of hypoelasticity (Hughes & Winget 1980, doi:10.1002/nme.1620151210).
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <span>

#include "common/types.hpp"

namespace common {

using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

/// The 9 doubles at `p` read as a row-major 3x3 (no copy): `Mat3 m = row_major(p);`.
inline Eigen::Map<const RowMajor3> row_major(const double* p) {
  return Eigen::Map<const RowMajor3>(p);
}
/// The 9 doubles at `p` written through as a row-major 3x3: `row_major_out(p) = m;`.
inline Eigen::Map<RowMajor3> row_major_out(double* p) { return Eigen::Map<RowMajor3>(p); }
/// Copy of `m` as 9 doubles, row-major ((0,0), (0,1), ..., (2,2)).
inline void to_row_major(const Mat3& m, std::span<double, 9> out) { row_major_out(out.data()) = m; }

/// Mean pressure p = -tr(sigma)/3 [Pa, compression positive] of a Cauchy stress (tension positive).
inline double pressure(const Mat3& sigma) { return -sigma.trace() / 3.0; }

/// Deviatoric stress q = sqrt(3/2 s:s), s the deviator of sigma [Pa].
inline double deviatoric(const Mat3& sigma) {
  const Mat3 s = sigma - sigma.trace() / 3.0 * Mat3::Identity();
  return std::sqrt(1.5 * (s.array() * s.array()).sum());
}

/// Lamé constants of an isotropic linear elastic solid [Pa] from Young's modulus E [Pa] and
/// Poisson's ratio nu [-] (nu in (-1, 0.5)).
struct Lame {
  double lambda = 0.0;
  double mu = 0.0;
};
inline Lame lame(double young, double poisson) {
  return {young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson)),
          young / (2.0 * (1.0 + poisson))};
}

/// One step of hypoelastic linear elasticity with the Hughes-Winget rotation: for a velocity
/// gradient L [1/s] held over h [s], sigma <- Q sigma Q^T + h (lambda tr(D) I + 2 mu D), with
/// Q = (I - h W / 2)^-1 (I + h W / 2) exactly orthogonal (objective). Built once per (L, h),
/// applied to any number of stresses or sub-steps.
struct HughesWinget {
  Mat3 Q;     ///< incremental rotation [-]
  Mat3 dsig;  ///< stress increment of the step, unrotated [Pa]
  HughesWinget(const Mat3& L, double h, const Lame& c) {
    const Mat3 I = Mat3::Identity();
    const Mat3 D = 0.5 * (L + L.transpose());
    const Mat3 W = 0.5 * (L - L.transpose());
    Q = (I - 0.5 * h * W).inverse() * (I + 0.5 * h * W);
    dsig = h * (c.lambda * D.trace() * I + 2.0 * c.mu * D);
  }
  [[nodiscard]] Mat3 apply(const Mat3& sigma) const { return Q * sigma * Q.transpose() + dsig; }
};

}  // namespace common
