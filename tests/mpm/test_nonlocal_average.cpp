// Tests of nonlocal_average.hpp (the pairs' sum) beyond the contract both averages share
// (test_point_average.cpp): a linear field is unchanged in the interior of a regular arrangement
// and a point source spreads as the cut Gaussian of standard deviation l, keeping its integral.
#include <gtest/gtest.h>

#include <cmath>

#include "mpm/nonlocal_average.hpp"
#include "plane_lattice.hpp"

namespace {

using common::Mat3;
using common::Vec3;

using mpm_test::filled;

/// n x n points of spacing h centred on 0 (a fresh lattice).
void lattice(int n, double h, std::vector<Vec3>& x, std::vector<double>& vol) {
  x.clear();
  vol.clear();
  mpm_test::plane_lattice(n, n, h, x, vol);
}

TEST(NonlocalAverage, LinearFieldUnchangedWhereTheKernelIsWhole) {
  const double h = 0.01, l = 0.0213;  // no lattice point exactly at the cut (3 l)
  std::vector<Vec3> x;
  std::vector<double> vol;
  lattice(40, h, x, vol);
  const Mat3 A = filled(1.0), B = filled(-3.0), C = filled(0.5);
  std::vector<Mat3> L;
  for (const Vec3& xp : x) L.push_back(A + xp[0] * B + xp[2] * C);
  const std::vector<std::int32_t> group(x.size(), 0);
  std::vector<Mat3> out;
  mpm::NonlocalAverage(l).apply(x, vol, group, L, out);
  const double inner = 0.5 * 39 * h - mpm::kNonlocalCutoff * l;
  int interior = 0;
  double worst_edge = 0.0;
  for (std::size_t p = 0; p < x.size(); ++p) {
    if (std::abs(x[p][0]) <= inner && std::abs(x[p][2]) <= inner) {
      // Symmetric weights on a symmetric lattice: the linear part cancels to rounding.
      EXPECT_LT((out[p] - L[p]).norm(), 1e-13 * A.norm()) << p;
      ++interior;
    } else {
      worst_edge = std::max(worst_edge, (out[p] - L[p]).norm());
    }
  }
  EXPECT_GT(interior, 100);
  // At the boundary the average is one-sided (the documented first-order error): it shows.
  EXPECT_GT(worst_edge, 1e-3 * A.norm());
}

TEST(NonlocalAverage, PointSourceSpreadsOverTheLength) {
  const double l = 0.03, h = l / 6.0;
  std::vector<Vec3> x;
  std::vector<double> vol;
  lattice(85, h, x, vol);  // +/- 7 l: every point that sees the source has a whole kernel
  const std::size_t source = x.size() / 2;
  ASSERT_LT(x[source].norm(), 1e-12);
  std::vector<Mat3> L(x.size(), Mat3::Zero());
  L[source] = Mat3::Identity();
  const std::vector<std::int32_t> group(x.size(), 0);
  std::vector<Mat3> out;
  mpm::NonlocalAverage(l).apply(x, vol, group, L, out);
  double integral = 0.0, second = 0.0, farthest = 0.0;
  for (std::size_t p = 0; p < x.size(); ++p) {
    const double f = out[p](0, 0);
    integral += vol[p] * f;
    second += vol[p] * f * x[p].squaredNorm();
    if (f != 0.0) farthest = std::max(farthest, x[p].norm());
  }
  // Every point near the source has the same kernel sum: the integral V_s L_s is kept (rounding).
  EXPECT_NEAR(integral, vol[source], 1e-12 * vol[source]);
  // The 2-D Gaussian cut at R = 3 l: <r^2> = 2 l^2 (1 - (1 + U) e^-U) / (1 - e^-U), U = R^2/(2 l^2)
  // = 4.5, i.e. a standard deviation per axis of 0.9744 l. Tolerance 1 %: the lattice's sampling
  // of the cut (h = l / 6), measured 0.3 %.
  const double U = 4.5;
  const double expected = l * std::sqrt((1 - (1 + U) * std::exp(-U)) / (1 - std::exp(-U)));
  EXPECT_NEAR(std::sqrt(second / integral / 2.0), expected, 0.01 * expected);
  EXPECT_LT(farthest, mpm::kNonlocalCutoff * l);
  EXPECT_GT(farthest, mpm::kNonlocalCutoff * l - 1.5 * h);
}

}  // namespace
