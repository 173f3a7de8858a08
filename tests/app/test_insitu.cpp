// Tests of app/setup/insitu.*: geostatic targets against rho g depth and K0, the pressure floor, the
// grouping of the targets (M distinct targets -> M preparations, a tolerance that merges them ->
// fewer, independent of the input order), the plan of a job, and the RVEs the coupled set-up
// makes from it (targets reached, pool of samples, independence of the creation order; the
// preparations made ahead over ranks and threads: test_dem_pool_mpi.cpp).
#include "app/setup/insitu.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "app/job/job.hpp"
#include "app/setup/coupled_setup.hpp"
#include "app/setup/mpm_setup.hpp"
#include "farm/dem_micro.hpp"
#include "insitu_test_job.hpp"

namespace {

using app_test::insitu_job;
using common::Mat3;
using common::Vec3;

// Gravity along -z: sigma_zz = -rho g depth, sigma_xx = sigma_yy = K0 sigma_zz, no shear. Exact
// up to round-off (1e-12 relative).
TEST(Insitu, GeostaticStressAlongZ) {
  const Mat3 s = app::geostatic_stress(1700.0, Vec3(0, 0, -9.81), 0.45, 3.0);
  const double sv = -1700.0 * 9.81 * 3.0;
  EXPECT_NEAR(s(2, 2), sv, 1e-12 * std::abs(sv));
  EXPECT_NEAR(s(0, 0), 0.45 * sv, 1e-12 * std::abs(sv));
  EXPECT_NEAR(s(1, 1), 0.45 * sv, 1e-12 * std::abs(sv));
  EXPECT_NEAR(s(0, 1), 0.0, 1e-12 * std::abs(sv));
  EXPECT_NEAR(s(0, 2), 0.0, 1e-12 * std::abs(sv));
  EXPECT_NEAR(s(1, 2), 0.0, 1e-12 * std::abs(sv));
}

// A tilted gravity: the stress along g is -rho |g| depth, across it K0 times that (eigenvectors).
TEST(Insitu, GeostaticStressAlongATiltedGravity) {
  const Vec3 g(3.0, -4.0, -12.0);  // |g| = 13
  const Mat3 s = app::geostatic_stress(2000.0, g, 0.6, 2.0);
  const Vec3 e = g.normalized();
  const Vec3 t = e.cross(Vec3(1, 0, 0)).normalized();
  const double sv = -2000.0 * 13.0 * 2.0;
  EXPECT_NEAR(e.dot(s * e), sv, 1e-12 * std::abs(sv));
  EXPECT_NEAR(t.dot(s * t), 0.6 * sv, 1e-12 * std::abs(sv));
  EXPECT_NEAR((s * e - sv * e).norm(), 0.0, 1e-12 * std::abs(sv));  // e is a principal direction
  EXPECT_NEAR(app::depth_below(Vec3(1.0, 2.0, 0.5), g, 4.0), 4.0 - Vec3(1.0, 2.0, 0.5).dot(-e),
              1e-15);
}

TEST(Insitu, PressureFloorScalesTheWholeTensor) {
  Mat3 s = app::geostatic_stress(1700.0, Vec3(0, 0, -10.0), 0.5, 0.1);  // p = 1133 Pa
  const Mat3 before = s;
  EXPECT_TRUE(app::apply_pressure_floor(s, 5e3));
  EXPECT_NEAR(-s.trace() / 3.0, 5e3, 1e-9);
  EXPECT_NEAR(s(0, 0) / s(2, 2), 0.5, 1e-14);  // the shape (K0) is kept
  EXPECT_NEAR((s - before * (5e3 / (-before.trace() / 3.0))).norm(), 0.0, 1e-9);
  Mat3 deep = app::geostatic_stress(1700.0, Vec3(0, 0, -10.0), 0.5, 10.0);
  const Mat3 d0 = deep;
  EXPECT_FALSE(app::apply_pressure_floor(deep, 5e3));
  EXPECT_EQ(deep, d0);
}

std::vector<Mat3> column_targets(int points_per_depth, int depths) {
  std::vector<Mat3> t;
  for (int k = 0; k < depths; ++k) {
    for (int i = 0; i < points_per_depth; ++i)
      t.push_back(app::geostatic_stress(1700.0, Vec3(0, 0, -9.81), 0.5, 0.5 + k));
  }
  return t;
}

// N = 24 points at M = 6 depths: 6 groups of 4 with tolerance 0; their representatives are the
// 6 targets. A tolerance larger than the relative step between depths merges them.
TEST(Insitu, GroupingMakesOnePreparationPerDistinctTarget) {
  const auto t = column_targets(4, 6);
  const app::Grouping g = app::group_targets(t, 0.0, 1e3);
  ASSERT_EQ(g.target.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(g.count[k], 4);
    EXPECT_EQ(g.target[k], t[4 * k]);  // ascending p: the depths in order
  }
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_EQ(g.target[g.group_of[i]], t[i]);
  // Depths 0.5, 1.5, ..., 5.5: sigma_zz grows by rho g x 1 m = 16.7 kPa per depth, the largest
  // component difference; the representative's p is 2/3 rho g depth (K0 = 0.5). Tolerance 0.7:
  // 0.5 | 1.5 | 2.5 + 3.5 (16.7 <= 0.7 x 27.8 kPa) | 4.5 + 5.5: 4 groups of 4, 4, 8, 8 points.
  const app::Grouping merged = app::group_targets(t, 0.7, 1e3);
  ASSERT_EQ(merged.target.size(), 4u);
  EXPECT_EQ(merged.count, (std::vector<std::int64_t>{4, 4, 8, 8}));
  EXPECT_EQ(merged.target[2], t[8]);
  EXPECT_EQ(merged.target[3], t[16]);
  // Every member is within the tolerance of its representative (the guarantee of the header).
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Mat3& r = merged.target[merged.group_of[i]];
    EXPECT_LE((t[i] - r).cwiseAbs().maxCoeff(), 0.7 * std::max(-r.trace() / 3.0, 1e3));
  }
}

// The grouping depends on the set of targets, not on their order (ranks see the same plan).
TEST(Insitu, GroupingIsIndependentOfTheInputOrder) {
  auto t = column_targets(3, 5);
  const app::Grouping a = app::group_targets(t, 0.3, 1e3);
  std::reverse(t.begin(), t.end());
  const app::Grouping b = app::group_targets(t, 0.3, 1e3);
  ASSERT_EQ(a.target.size(), b.target.size());
  for (std::size_t k = 0; k < a.target.size(); ++k) {
    EXPECT_EQ(a.target[k], b.target[k]);
    EXPECT_EQ(a.count[k], b.count[k]);
  }
}

TEST(Insitu, SampleOfPointIdIsIdModK) {
  EXPECT_EQ(app::sample_of(0, 1), 0);
  EXPECT_EQ(app::sample_of(7, 1), 0);
  EXPECT_EQ(app::sample_of(7, 3), 1);
  EXPECT_EQ(app::sample_of(9, 3), 0);
  app::InsituOptions o;
  o.samples = 3;
  EXPECT_EQ(app::sample_of(7, o), 1);  // in turn by default
}

// Scattered: a pure function of (id, seed) that is not id mod K. On a row of 16 points drawing
// from 4 samples, in turn gives each vertical line of points one sample (id mod 4 is the line's
// index mod 4); scattered must give the lines several samples, draw every sample about as often
// (within 5 sigma of a binomial over 4096 points) and another seed must give another draw.
TEST(Insitu, ScatteredDrawHasNoPatternInSpace) {
  app::InsituOptions o;
  o.samples = 4;
  o.draw = app::SampleDraw::scattered;
  o.draw_seed = 3;
  constexpr int kRow = 16;
  constexpr int kRows = 256;
  std::array<int, 4> count{};
  int lines_with_one_sample = 0;
  for (int i = 0; i < kRow; ++i) {
    std::set<std::int64_t> in_line;
    for (int j = 0; j < kRows; ++j) {
      const std::int64_t s = app::sample_of(std::int64_t{j} * kRow + i, o);
      ASSERT_GE(s, 0);
      ASSERT_LT(s, 4);
      EXPECT_EQ(s, app::sample_of(std::int64_t{j} * kRow + i, o));  // deterministic
      in_line.insert(s);
      ++count[static_cast<std::size_t>(s)];
    }
    if (in_line.size() == 1) ++lines_with_one_sample;
  }
  EXPECT_EQ(lines_with_one_sample, 0);
  const double n = kRow * kRows;
  const double sigma = std::sqrt(n * 0.25 * 0.75);
  for (const int c : count) EXPECT_LE(std::abs(c - 0.25 * n), 5.0 * sigma) << c;
  app::InsituOptions other = o;
  other.draw_seed = 19;
  int same = 0;
  for (std::int64_t id = 0; id < 4096; ++id)
    same += app::sample_of(id, o) == app::sample_of(id, other);
  EXPECT_LT(same, 0.35 * 4096);  // two independent draws agree on about a quarter of the points
}

const char* kFloor = R"(
[dem.initial_state]
pressure_floor = "10 kPa"
group_tolerance = 0.01
)";

TEST(Insitu, PlanOfAJob) {
  const app::Job job = app::Job::parse(insitu_job(kFloor), "insitu.toml");
  const app::MpmSetup setup = app::mpm_setup(job);
  const app::InsituPlan plan = app::insitu_plan(job, setup);
  ASSERT_EQ(plan.ids.size(), 4u);  // ids 0, 1: the column (z = 0.5, 1.5), 2: uniform, 3: prepared
  EXPECT_EQ(plan.floored, 1);
  EXPECT_EQ(plan.group_of(3), -1);
  EXPECT_EQ(plan.groups.target.size(), 3u);
  EXPECT_EQ(plan.preparations(), 4);  // 3 groups and the prepared sample itself
  // The deep point: depth 1.5 m, not floored (p = 16.7 kPa).
  const Mat3 deep = plan.groups.target[static_cast<std::size_t>(plan.group_of(0))];
  EXPECT_NEAR(deep(2, 2), -1700.0 * 9.81 * 1.5, 1e-9);
  EXPECT_NEAR(deep(0, 0), 0.5 * deep(2, 2), 1e-9);
  // The shallow point: depth 0.5 m, p = 5.56 kPa floored to 10 kPa with K0 kept.
  const Mat3 top = plan.groups.target[static_cast<std::size_t>(plan.group_of(1))];
  EXPECT_NEAR(-top.trace() / 3.0, 1e4, 1e-9);
  EXPECT_NEAR(top(0, 0) / top(2, 2), 0.5, 1e-12);
  const Mat3 uni = plan.groups.target[static_cast<std::size_t>(plan.group_of(2))];
  EXPECT_EQ(uni(2, 2), -60e3);
  EXPECT_EQ(uni(0, 2), 5e3);
  EXPECT_EQ(uni(2, 0), 5e3);
}

// The RVEs of the coupled set-up start at their targets (the servo tolerance of 1 % per diagonal
// component and 1 % of p off the diagonal), the prepared body at the preparation pressure (its
// tolerance, 2 %); and a point's RVE does not depend on which points were created before it (a
// rank that owns only point 2 gets the same bits as one that made 0, 1, 2, 3).
TEST(Insitu, CoupledSetupStartsEveryRveAtItsTarget) {
  const app::Job job = app::Job::parse(insitu_job(kFloor), "insitu.toml");
  const app::MpmSetup setup = app::mpm_setup(job);
  const app::InsituPlan plan = app::insitu_plan(job, setup);
  const farm::CoupledConfig cfg = app::coupled_setup(job, app::RunLimits{"unused", -1});
  std::vector<Mat3> stress;
  for (std::int64_t id = 0; id < 4; ++id) stress.push_back(cfg.micro.create(id)->stress());
  for (std::int64_t id = 0; id < 3; ++id) {
    const Mat3& t = plan.groups.target[static_cast<std::size_t>(plan.group_of(id))];
    const double p = -t.trace() / 3.0;
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(std::abs(stress[id](a, a) / t(a, a) - 1.0), 0.01) << id << " " << a;
      for (int b = a + 1; b < 3; ++b)
        EXPECT_LE(std::abs(stress[id](a, b) - t(a, b)), 0.01 * p) << id << " " << a << b;
    }
  }
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(-stress[3](a, a), 50e3, 0.02 * 50e3);
  const farm::CoupledConfig other = app::coupled_setup(job, app::RunLimits{"unused", -1});
  EXPECT_EQ(other.micro.create(2)->stress(), stress[2]);
}

// A pool of 2 samples: points 0 and 2 (even ids) draw sample 0, points 1 and 3 sample 1. The two
// prepared points (one per sample) differ; the uniform body's point (id 2, sample 0) reaches its
// target from sample 0. 4 groups/samples pairs are needed.
TEST(Insitu, PoolOfSamplesGivesDistinctRves) {
  const app::Job job = app::Job::parse(insitu_job(R"(
[dem.initial_state]
pressure_floor = "10 kPa"
samples = 2
)"),
                                       "insitu.toml");
  const app::MpmSetup setup = app::mpm_setup(job);
  const app::InsituPlan plan = app::insitu_plan(job, setup);
  EXPECT_EQ(plan.preparations(), 4);
  const farm::CoupledConfig cfg = app::coupled_setup(job, app::RunLimits{"unused", -1});
  const auto m3 = cfg.micro.create(3);  // prepared, sample 1
  const auto* d3 = dynamic_cast<const farm::DemMicro*>(m3.get());
  ASSERT_NE(d3, nullptr);
  // Point 2's RVE is sample 0 brought to the uniform target: other spheres than sample 1's.
  const auto m2 = cfg.micro.create(2);
  const auto* d2 = dynamic_cast<const farm::DemMicro*>(m2.get());
  ASSERT_NE(d2, nullptr);
  EXPECT_NE(d2->rve().simulation().spheres().r, d3->rve().simulation().spheres().r);
  EXPECT_NEAR(m2->stress()(2, 2), -60e3, 0.01 * 60e3);
}

// The farm calls micro.prepare with a rank's ids before it creates their RVEs: the samples and
// the (group, sample) preparations are then made on the rank's threads, several at once. Each
// RVE must be the same bits as the one created alone, lazily (2 samples x 3 groups and the
// prepared body: 4 preparations for the 4 points; with 3 threads, 2 samples at once, then 3
// groups at once). Compared: the stress, every sphere's position, velocity and spin, the step.
}  // namespace
