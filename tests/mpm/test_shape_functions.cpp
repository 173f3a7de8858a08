// Tests of shape_linear.hpp, shape_ugimp.hpp, shape_bspline2.hpp, shape_function.hpp:
// partition of unity, linear completeness, gradients summing to zero, gradient = derivative.
#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.hpp"
#include "mpm/shape_function.hpp"

namespace {

using mpm::ShapeKind;

// Round-off bound: sums of 2-3 terms of size <= 1 (values) or 1/h (gradients); 1e-14 is ~50 ulp.
constexpr double kTol = 1e-14;

struct Case {
  ShapeKind kind;
  double lp;  // half-width in cell units (uGIMP)
};

class ShapeFunctions : public ::testing::TestWithParam<Case> {};

TEST_P(ShapeFunctions, PartitionOfUnityCompletenessAndGradients) {
  const Case c = GetParam();
  const double h = 0.5;
  for (int k = 0; k <= 400; ++k) {
    const double s = 2.0 + 3.0 * k / 400.0;  // well inside a grid with nodes 0..10
    const mpm::Weights1D w = mpm::weights_1d(c.kind, s, c.lp, h);
    double sum = 0.0, first = 0.0, dsum = 0.0, dfirst = 0.0;
    for (int a = 0; a < mpm::stencil_width(c.kind); ++a) {
      const double x_i = (w.base + a) * h;
      sum += w.w[a];
      first += w.w[a] * x_i;
      dsum += w.dw[a];
      dfirst += w.dw[a] * x_i;
    }
    EXPECT_NEAR(sum, 1.0, kTol) << "s = " << s;
    EXPECT_NEAR(first, s * h, kTol * 10) << "s = " << s;  // sum S_i x_i = x
    EXPECT_NEAR(dsum, 0.0, kTol / h) << "s = " << s;      // sum grad S_i = 0
    EXPECT_NEAR(dfirst, 1.0, kTol * 10) << "s = " << s;   // sum grad S_i x_i = 1
  }
}

TEST_P(ShapeFunctions, GradientIsTheDerivativeOfTheValue) {
  const Case c = GetParam();
  const double h = 1.0;
  const double eps = 1e-6;
  for (int k = 0; k < 97; ++k) {
    const double s = 3.013 + 2.0 * k / 97.0;
    const mpm::Weights1D w = mpm::weights_1d(c.kind, s, c.lp, h);
    for (int a = 0; a < mpm::stencil_width(c.kind); ++a) {
      const double r = s - (w.base + a);
      double vp = 0.0, vm = 0.0;
      switch (c.kind) {
        case ShapeKind::linear:
          vp = mpm::LinearShape::value(r + eps, c.lp);
          vm = mpm::LinearShape::value(r - eps, c.lp);
          break;
        case ShapeKind::ugimp:
          vp = mpm::UgimpShape::value(r + eps, c.lp);
          vm = mpm::UgimpShape::value(r - eps, c.lp);
          break;
        case ShapeKind::bspline2:
          vp = mpm::BSpline2Shape::value(r + eps, c.lp);
          vm = mpm::BSpline2Shape::value(r - eps, c.lp);
          break;
      }
      // Central difference: exact for the piecewise polynomials away from kinks (1e-6 accounts
      // for cancellation); the sampled s avoid kinks by more than eps.
      EXPECT_NEAR(w.dw[a], (vp - vm) / (2 * eps), 1e-6) << "s = " << s << " a = " << a;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllKinds, ShapeFunctions,
                         ::testing::Values(Case{ShapeKind::linear, 0.0},
                                           Case{ShapeKind::ugimp, 0.25},
                                           Case{ShapeKind::ugimp, 0.5}, Case{ShapeKind::ugimp, 0.1},
                                           Case{ShapeKind::bspline2, 0.0}),
                         [](const auto& param_info) {
                           return std::string(mpm::to_string(param_info.param.kind)) + "_" +
                                  std::to_string(param_info.index);
                         });

TEST(ShapeFunctionNames, RoundTripAndRejectUnknown) {
  for (ShapeKind k : {ShapeKind::linear, ShapeKind::ugimp, ShapeKind::bspline2}) {
    EXPECT_EQ(mpm::shape_kind_from_string(mpm::to_string(k)), k);
  }
  try {
    (void)mpm::shape_kind_from_string("cubic");
    FAIL() << "no throw";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("linear, ugimp, bspline2"), std::string::npos);
  }
}

TEST(ShapeFunctionValues, KnownValues) {
  // Linear: the paper's Gauss-like points 1/4, 3/4.
  EXPECT_DOUBLE_EQ(mpm::LinearShape::value(0.25, 0), 0.75);
  // uGIMP with lp = 1/4 at r = 0: 1 - lp / 2.
  EXPECT_DOUBLE_EQ(mpm::UgimpShape::value(0.0, 0.25), 1.0 - 0.125);
  // B-spline at a node: 3/4, neighbours 1/8.
  EXPECT_DOUBLE_EQ(mpm::BSpline2Shape::value(0.0, 0), 0.75);
  EXPECT_DOUBLE_EQ(mpm::BSpline2Shape::value(1.0, 0), 0.125);
}

}  // namespace
