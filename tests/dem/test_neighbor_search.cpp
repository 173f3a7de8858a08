// Neighbour search against brute force on a sheared cell; lattice re-mapping keeps branches.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <tuple>

#include "common/errors.hpp"
#include "dem/neighbor_search.hpp"

namespace {

using common::Mat3;
using common::Vec3;

dem::Spheres random_spheres(const Mat3& h, int n, std::uint64_t seed) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  dem::Spheres s;
  for (int i = 0; i < n; ++i) s.add(h * Vec3(u(g), u(g), u(g)), 0.05 + 0.05 * u(g), 1.0);
  return s;
}

using Pair = std::tuple<int, int, int, int, int>;

std::set<Pair> brute(const dem::Spheres& s, const Mat3& h, double skin) {
  std::set<Pair> out;
  for (int i = 0; i < static_cast<int>(s.size()); ++i) {
    for (int j = i + 1; j < static_cast<int>(s.size()); ++j) {
      for (int a = -2; a <= 2; ++a) {
        for (int b = -2; b <= 2; ++b) {
          for (int c = -2; c <= 2; ++c) {
            const Vec3 d = s.x[j] + h * Vec3(a, b, c) - s.x[i];
            if (d.norm() < s.r[i] + s.r[j] + skin) out.insert({i, j, a, b, c});
          }
        }
      }
    }
  }
  return out;
}

TEST(NeighborSearch, MatchesBruteForceInShearedCell) {
  dem::PeriodicCell cell;
  cell.h << 1.0, 0.4, 0.1, 0.0, 1.2, -0.3, 0.0, 0.0, 0.9;
  dem::Spheres s = random_spheres(cell.h, 300, 7);
  dem::Contacts c;
  dem::remap_and_wrap(s, cell, c, 0.5);
  dem::VerletState vs;
  vs.skin = 0.02;
  dem::build_pairs(s, cell, c, vs);
  std::set<Pair> got;
  for (std::size_t p = 0; p < c.size(); ++p) {
    got.insert({c.i[p], c.j[p], c.k[p][0], c.k[p][1], c.k[p][2]});
  }
  EXPECT_EQ(got.size(), c.size());
  EXPECT_EQ(got, brute(s, cell.h, vs.skin));
  EXPECT_FALSE(dem::needs_rebuild(s, cell, vs));
}

TEST(NeighborSearch, RemapKeepsBranchVectors) {
  dem::PeriodicCell cell;
  cell.h << 1.0, 1.7, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0;  // strongly sheared
  dem::Spheres s = random_spheres(cell.h, 200, 3);
  dem::Contacts c;
  dem::VerletState vs;
  vs.skin = 0.02;
  dem::remap_and_wrap(s, cell, c, 10.0);  // wrap only
  dem::build_pairs(s, cell, c, vs);
  std::vector<Vec3> before;
  for (std::size_t p = 0; p < c.size(); ++p) {
    before.push_back(s.x[c.j[p]] + cell.h * c.k[p].cast<double>() - s.x[c.i[p]]);
  }
  const Mat3 h0 = cell.h;
  ASSERT_TRUE(dem::remap_and_wrap(s, cell, c, 0.5));
  EXPECT_LT(std::abs(cell.h(0, 1)), 0.5 + 1e-12);
  EXPECT_NEAR(cell.h.determinant(), h0.determinant(), 1e-12);
  for (std::size_t p = 0; p < c.size(); ++p) {
    const Vec3 d = s.x[c.j[p]] + cell.h * c.k[p].cast<double>() - s.x[c.i[p]];
    EXPECT_LT((d - before[p]).norm(), 1e-12);
  }
}

}  // namespace

// An active contact that the new list lacks has separated: with the adaptive skin (a thin list,
// skin_max the widest) it ends if it is within r_i + r_j + skin_max, and is the numerical failure
// of a step too large for the packing beyond; with the fixed skin (skin_max 0) beyond the skin.
TEST(NeighborSearch, SeparatedContactEndsWithinTheWidestSkin) {
  const auto attempt = [](double x2, double skin_max) {
    dem::PeriodicCell cell;
    cell.h = Mat3::Identity();
    dem::Spheres s;
    s.add(Vec3(0.2, 0.5, 0.5), 0.1, 1.0);
    s.add(Vec3(0.39, 0.5, 0.5), 0.1, 1.0);  // overlap 0.01
    dem::Contacts c;
    dem::VerletState vs;
    vs.skin = 0.003;
    vs.skin_max = skin_max;
    dem::build_pairs(s, cell, c, vs);
    EXPECT_EQ(c.size(), 1u);
    c.active[0] = 1;  // touching at the last force pass
    s.x[1] = Vec3(x2, 0.5, 0.5);
    dem::build_pairs(s, cell, c, vs);
    return c.size();
  };
  EXPECT_EQ(attempt(0.405, 0.01), 0u);  // gap 0.005: beyond the thin skin, within the widest
  EXPECT_EQ(attempt(0.402, 0.0), 1u);   // gap 0.002: still listed, history carried
  EXPECT_THROW((void)attempt(0.42, 0.01), common::NumericalError);  // gap 0.02 > skin_max
  EXPECT_THROW((void)attempt(0.405, 0.0), common::NumericalError);  // the fixed skin's rule
}
