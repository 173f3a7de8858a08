// The contract of point_average.hpp, for both averages (the pairs' sum, nonlocal_average.hpp, and
// the lattice's, lattice_average.hpp): a homogeneous field is unchanged everywhere, materials are
// not mixed, threads do not change a bit, the adjoint is the transpose in the volume-weighted
// product, and a length that is not > 0 is refused.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <random>

#include "common/errors.hpp"
#include "mpm/lattice_average.hpp"
#include "mpm/nonlocal_average.hpp"
#include "plane_lattice.hpp"

namespace {

using common::Mat3;
using common::Vec3;

using mpm_test::filled;

template <class Average>
class PointAverage : public ::testing::Test {};
using Averages = ::testing::Types<mpm::NonlocalAverage, mpm::LatticeAverage>;
TYPED_TEST_SUITE(PointAverage, Averages);

TYPED_TEST(PointAverage, HomogeneousFieldUnchangedEverywhere) {
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
  TypeParam avg(0.1);
  avg.apply(x, vol, group, L, out);
  // A normalised mean of equal tensors: a few ulps of |L| ~ 3.
  for (std::size_t p = 0; p < x.size(); ++p) EXPECT_LT((out[p] - L[p]).norm(), 1e-14) << p;
}

TYPED_TEST(PointAverage, MaterialsAreNotMixed) {
  const double h = 0.01;
  std::vector<Vec3> x;
  std::vector<double> vol;
  mpm_test::plane_lattice(12, 12, h, x, vol);
  std::vector<std::int32_t> group;
  std::vector<Mat3> L;
  for (std::size_t p = 0; p < x.size(); ++p) {
    group.push_back(p % 3 == 0 ? 7 : -2);  // any ids
    L.push_back(filled(group.back() == 7 ? 2.0 : -1.0));
  }
  std::vector<Mat3> out;
  TypeParam(0.02).apply(x, vol, group, L, out);
  for (std::size_t p = 0; p < x.size(); ++p) EXPECT_LT((out[p] - L[p]).norm(), 1e-14) << p;
}

TYPED_TEST(PointAverage, ThreadCountDoesNotChangeABit) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> x;
  std::vector<double> vol;
  std::vector<Mat3> L;
  for (int p = 0; p < 6000; ++p) {  // above kMinParallelPoints: parallel loops
    x.emplace_back(u(rng), 0.1 * u(rng), u(rng));
    vol.push_back(1.5 + u(rng));
    L.push_back(filled(u(rng)));
  }
  const std::vector<std::int32_t> group(x.size(), 0);
  std::vector<Mat3> one, three, adj_one, adj_three;
  TypeParam avg(0.05);
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  avg.apply(x, vol, group, L, one);
  avg.apply_adjoint(L, adj_one);
  omp_set_num_threads(3);
  avg.apply(x, vol, group, L, three);
  avg.apply_adjoint(L, adj_three);
  omp_set_num_threads(before);
  for (std::size_t p = 0; p < x.size(); ++p) {
    ASSERT_TRUE(one[p] == three[p]) << p;
    ASSERT_TRUE(adj_one[p] == adj_three[p]) << p;
  }
}

// The stress of the internal forces: <sigma, N L>_V = <N^T sigma, L>_V for any fields (the forces'
// power on the points' L is the materials' on the average), and N^T keeps the integral.
TYPED_TEST(PointAverage, AdjointIsTheTransposeInTheVolumeProduct) {
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
  TypeParam avg(0.2);
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

TYPED_TEST(PointAverage, RefusesANonPositiveLength) {
  EXPECT_THROW(TypeParam(0.0), common::InputError);
  EXPECT_THROW(TypeParam(-1e-3), common::InputError);
  EXPECT_THROW(TypeParam(std::nan("")), common::InputError);
}

}  // namespace
