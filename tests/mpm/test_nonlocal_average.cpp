// Tests of nonlocal_average.hpp: a homogeneous field is unchanged everywhere, a linear one in the
// interior of a regular arrangement, a point source spreads as the cut Gaussian of standard
// deviation l and keeps its integral, materials are not mixed, threads do not change a bit, and
// the adjoint is the transpose in the volume-weighted product.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <random>

#include "common/errors.hpp"
#include "mpm/nonlocal_average.hpp"
#include "plane_lattice.hpp"

namespace {

using common::Mat3;
using common::Vec3;

Mat3 filled(double a) {
  Mat3 m;
  m << a, 2 * a, 3 * a, -a, 0.5 * a, 0.0, 0.25 * a, a, -2 * a;
  return m;
}

/// n x n points of spacing h centred on 0 (a fresh lattice).
void lattice(int n, double h, std::vector<Vec3>& x, std::vector<double>& vol) {
  x.clear();
  vol.clear();
  mpm_test::plane_lattice(n, n, h, x, vol);
}

TEST(NonlocalAverage, HomogeneousFieldUnchangedEverywhere) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> x;
  std::vector<double> vol;
  for (int p = 0; p < 300; ++p) {
    x.emplace_back(u(rng), 0.3 * u(rng), 2.0 * u(rng));
    vol.push_back(0.1 + u(rng));
  }
  const std::vector<std::int32_t> group(x.size(), 0);
  const std::vector<Mat3> L(x.size(), filled(0.7));
  std::vector<Mat3> out;
  mpm::NonlocalAverage avg(0.1);
  avg.apply(x, vol, group, L, out);
  // A normalised mean of equal tensors: a few ulps of |L| ~ 3.
  for (std::size_t p = 0; p < x.size(); ++p) EXPECT_LT((out[p] - L[p]).norm(), 1e-14) << p;
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

TEST(NonlocalAverage, MaterialsAreNotMixed) {
  const double h = 0.01;
  std::vector<Vec3> x;
  std::vector<double> vol;
  lattice(12, h, x, vol);
  std::vector<std::int32_t> group;
  std::vector<Mat3> L;
  for (std::size_t p = 0; p < x.size(); ++p) {
    group.push_back(static_cast<std::int32_t>(p % 3 == 0));
    L.push_back(filled(group.back() == 1 ? 2.0 : -1.0));
  }
  std::vector<Mat3> out;
  mpm::NonlocalAverage(0.02).apply(x, vol, group, L, out);
  for (std::size_t p = 0; p < x.size(); ++p) EXPECT_LT((out[p] - L[p]).norm(), 1e-14) << p;
}

TEST(NonlocalAverage, ThreadCountDoesNotChangeABit) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> x;
  std::vector<double> vol;
  std::vector<Mat3> L;
  for (int p = 0; p < 6000; ++p) {  // above kMinParallelPoints: a parallel loop
    x.emplace_back(u(rng), 0.1 * u(rng), u(rng));
    vol.push_back(1.5 + u(rng));
    L.push_back(filled(u(rng)));
  }
  const std::vector<std::int32_t> group(x.size(), 0);
  std::vector<Mat3> one, three;
  mpm::NonlocalAverage avg(0.05);
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  avg.apply(x, vol, group, L, one);
  omp_set_num_threads(3);
  avg.apply(x, vol, group, L, three);
  omp_set_num_threads(before);
  for (std::size_t p = 0; p < x.size(); ++p) ASSERT_TRUE(one[p] == three[p]) << p;
}

// The stress of the internal forces: <sigma, N L>_V = <N^T sigma, L>_V for any fields (the forces'
// power on the points' L is the materials' on the average), and N^T keeps the integral.
TEST(NonlocalAverage, AdjointIsTheTransposeInTheVolumeProduct) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> x;
  std::vector<double> vol;
  std::vector<Mat3> L, sigma;
  std::vector<std::int32_t> group;
  for (int p = 0; p < 400; ++p) {
    x.emplace_back(u(rng), 0.0, 2.0 * u(rng));
    vol.push_back(1.5 + u(rng));
    L.push_back(filled(u(rng)) + u(rng) * Mat3::Identity());
    sigma.push_back(filled(u(rng)).transpose() + u(rng) * Mat3::Identity());
    group.push_back(p % 5 == 0 ? 1 : 0);
  }
  mpm::NonlocalAverage avg(0.2);
  std::vector<Mat3> NL, Ns;
  avg.apply(x, vol, group, L, NL);
  avg.apply_adjoint(x, vol, group, sigma, Ns);
  double lhs = 0.0, rhs = 0.0, scale = 0.0;
  Mat3 before = Mat3::Zero(), after = Mat3::Zero();
  for (std::size_t p = 0; p < x.size(); ++p) {
    lhs += vol[p] * sigma[p].cwiseProduct(NL[p]).sum();
    rhs += vol[p] * Ns[p].cwiseProduct(L[p]).sum();
    scale += vol[p] * sigma[p].norm() * L[p].norm();
    before += vol[p] * sigma[p];
    after += vol[p] * Ns[p];
  }
  // Sums of 400 terms of order 1 in another order: 1e-13 of their magnitude is rounding.
  EXPECT_NEAR(lhs, rhs, 1e-13 * scale);
  EXPECT_LT((before - after).norm(), 1e-13 * scale);
  // It is not the plain average (the kernel sums differ near the edges): the test can fail.
  std::vector<Mat3> plain;
  avg.apply(x, vol, group, sigma, plain);
  double differ = 0.0;
  for (std::size_t p = 0; p < x.size(); ++p) differ = std::max(differ, (plain[p] - Ns[p]).norm());
  EXPECT_GT(differ, 1e-3);
}

TEST(NonlocalAverage, RefusesANonPositiveLength) {
  EXPECT_THROW(mpm::NonlocalAverage(0.0), common::InputError);
  EXPECT_THROW(mpm::NonlocalAverage(-1e-3), common::InputError);
  EXPECT_THROW(mpm::NonlocalAverage(std::nan("")), common::InputError);
}

}  // namespace
