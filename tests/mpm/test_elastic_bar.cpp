// Verification: 1D elastic bar, first mode (verification_cases.hpp, run_elastic_bar).
#include <gtest/gtest.h>

#include <cstdio>

#include "mpm/verification_cases.hpp"

namespace {

// Period within 1 % of 4 L / c (the requirement). The measured errors (docs/design/mpm.md) are
// 5e-4 to 7e-4 for linear and uGIMP on 25 cells: the 1 % bound is the requirement, not a fit.
// Energy: NFLIP + USF is not exactly conservative; the drift is reported, and bounded by 1 %
// over two periods (measured 0.46 %) only to catch regressions.
void check(mpm::ShapeKind shape, int cells, mpm::StressUpdate scheme) {
  const mpm::BarResult r = mpm::run_elastic_bar(shape, cells, 2.0, 0.1, scheme);
  std::printf(
      "bar %s cells=%d: period %.6f s (analytic %.1f, rel. error %.3e), energy drift %.3e\n",
      mpm::to_string(shape).data(), cells, r.period, r.period_analytic,
      r.period / r.period_analytic - 1, r.energy_drift);
  ::testing::Test::RecordProperty("period", std::to_string(r.period));
  ::testing::Test::RecordProperty("energy_drift", std::to_string(r.energy_drift));
  EXPECT_NEAR(r.period, r.period_analytic, 0.01 * r.period_analytic);
  EXPECT_LT(r.energy_drift, 0.01);
}

TEST(ElasticBar, LinearUsfPeriodWithin1Percent) {
  check(mpm::ShapeKind::linear, 25, mpm::StressUpdate::usf);
}
TEST(ElasticBar, LinearMuslPeriodWithin1Percent) {
  check(mpm::ShapeKind::linear, 25, mpm::StressUpdate::musl);
}
TEST(ElasticBar, UgimpUsfPeriodWithin1Percent) {
  check(mpm::ShapeKind::ugimp, 25, mpm::StressUpdate::usf);
}
// The B-spline's fixed end is imposed by fixing the nodes at x <= 0, which leaves v(0) = v_1 / 8:
// the bar is effectively about h / 3 longer, an O(h) error (1.3 % on 25 cells, 0.65 % on 50).
// Hence 50 cells here; see docs/design/mpm.md (known limitation).
TEST(ElasticBar, BSplineUsf50CellsPeriodWithin1Percent) {
  check(mpm::ShapeKind::bspline2, 50, mpm::StressUpdate::usf);
}

}  // namespace
