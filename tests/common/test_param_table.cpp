// common::ParamTable: ranges and their rules, rows reading and writing members, defaults taken from
// the member initializers, and errors that name the key.
#include "common/param_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "common/errors.hpp"

namespace {

using common::Source;
using common::Unit;

struct Knobs {
  double stiffness = 0.0;      // required in a job
  double safety = 0.8;         // job default 0.8
  std::int64_t refresh = 100;  // C++ only
  double angle = 30.0;
  int axis = 2;  // C++ only, an int member
};

constexpr auto kKnobs = common::make_table<Knobs>(
    "test::Knobs", "sec.knobs",
    {{"stiffness", &Knobs::stiffness, Unit::Pressure, common::gt(0), Source::job_required, "k"},
     {"safety", &Knobs::safety, Unit::Dimensionless, common::in_oc(0, 1), Source::job_default, "s"},
     {"refresh", &Knobs::refresh, Unit::Dimensionless, common::ge(1), Source::cpp_only, "r"},
     {"sub.angle", &Knobs::angle, Unit::Angle, common::in_co(0, 90), Source::job_default, "a"},
     {"axis", &Knobs::axis, Unit::Dimensionless, common::in_cc(0, 2), Source::cpp_only, "x"}});

std::string error_of(const Knobs& k) {
  try {
    common::check_ranges(kKnobs, k);
  } catch (const common::InputError& e) {
    return e.what();
  }
  return {};
}

TEST(ParamTable, RangesIncludeOrExcludeTheirBoundsAndRejectNonFiniteValues) {
  EXPECT_FALSE(common::gt(0).contains(0.0));
  EXPECT_TRUE(common::ge(0).contains(0.0));
  EXPECT_TRUE(common::in_co(0, 90).contains(0.0));
  EXPECT_FALSE(common::in_co(0, 90).contains(90.0));
  EXPECT_FALSE(common::in_oc(0, 1).contains(0.0));
  EXPECT_TRUE(common::in_oc(0, 1).contains(1.0));
  EXPECT_TRUE(common::in_cc(0, 1).contains(1.0));
  EXPECT_FALSE(common::in_oo(0, 1).contains(1.0));
  EXPECT_TRUE(common::any().contains(-1e300));
  EXPECT_FALSE(common::any().contains(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_FALSE(common::ge(0).contains(std::numeric_limits<double>::infinity()));
}

TEST(ParamTable, RulesReadAsTheJobErrorsWriteThem) {
  EXPECT_EQ(common::in_co(0, 90).rule(Unit::Angle), "must be in [0, 90) deg");
  EXPECT_EQ(common::gt(0).rule(Unit::Pressure), "must be > 0 Pa");
  EXPECT_EQ(common::ge(0.5).rule(Unit::Dimensionless), "must be >= 0.5");
  EXPECT_EQ(common::in_oo(0, 1).rule(Unit::Dimensionless), "must be in (0, 1)");
  EXPECT_EQ(common::in_oc(1e-5, 1).rule(Unit::Dimensionless), "must be in (1e-05, 1]");
  EXPECT_EQ(common::any().rule(Unit::Dimensionless), "must be a finite number");
}

TEST(ParamTable, RowsReadAndWriteTheirMembersAndTakeDefaultsFromTheInitializers) {
  Knobs k;
  const auto& refresh = kKnobs.rows[2];
  EXPECT_TRUE(refresh.is_integer());
  refresh.set(k, 7.0);
  EXPECT_EQ(k.refresh, 7);
  EXPECT_EQ(refresh.get(k), 7.0);
  kKnobs.rows[1].set(k, 0.5);
  EXPECT_EQ(k.safety, 0.5);
  EXPECT_EQ(kKnobs.rows[1].default_value(), 0.8);
  EXPECT_EQ(refresh.default_value(), 100.0);
  EXPECT_EQ(kKnobs.name(kKnobs.rows[3]), "sec.knobs.sub.angle");
  EXPECT_EQ(kKnobs.name(refresh), "test::Knobs::refresh");
  EXPECT_FALSE(refresh.in_job());
}

TEST(ParamTable, IntMembersAreIntegerRowsClampedToTheRangeOfInt) {
  Knobs k;
  const auto& axis = kKnobs.rows[4];
  EXPECT_TRUE(axis.is_integer());
  EXPECT_EQ(axis.default_value(), 2.0);
  axis.set(k, 1.0);
  EXPECT_EQ(k.axis, 1);
  axis.set(k, 1e12);
  EXPECT_EQ(k.axis, std::numeric_limits<int>::max());
  k.stiffness = 1.0;
  EXPECT_EQ(error_of(k), "test::Knobs::axis = 2147483647: must be in [0, 2]");
}

// A job's integer is set exactly (set_integer): through a double, 2^63 - 1 became 2^63, whose
// conversion to int64 is undefined (it gave -2^63, reported as "= -9223372036854775808: must be
// >= 1" for every integer key). A double beyond the int64 range is clamped, NaN gives 0.
TEST(ParamTable, IntegersAreSetExactlyAndDoublesBeyondTheRangeClamped) {
  Knobs k;
  const auto& refresh = kKnobs.rows[2];
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  refresh.set_integer(k, kMax);
  EXPECT_EQ(k.refresh, kMax);
  refresh.set_integer(k, (std::int64_t{1} << 53) + 1);  // not a double
  EXPECT_EQ(k.refresh, (std::int64_t{1} << 53) + 1);
  refresh.set(k, static_cast<double>(kMax));  // 2^63
  EXPECT_EQ(k.refresh, kMax);
  refresh.set(k, -1e300);
  EXPECT_EQ(k.refresh, std::numeric_limits<std::int64_t>::min());
  refresh.set(k, std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(k.refresh, 0);
  const auto& axis = kKnobs.rows[4];
  axis.set_integer(k, kMax);
  EXPECT_EQ(k.axis, std::numeric_limits<int>::max());
  axis.set_integer(k, -5);
  EXPECT_EQ(k.axis, -5);
  kKnobs.rows[1].set_integer(k, 3);
  EXPECT_EQ(k.safety, 3.0);
}

TEST(ParamTable, CheckNamesTheFirstKeyOutOfRangeWithValueAndRule) {
  Knobs k;
  EXPECT_EQ(error_of(k), "sec.knobs.stiffness = 0: must be > 0 Pa");
  k.stiffness = 1e9;
  EXPECT_EQ(error_of(k), "");
  k.angle = 90.0;
  EXPECT_EQ(error_of(k), "sec.knobs.sub.angle = 90: must be in [0, 90) deg");
  k.angle = 30.0;
  k.refresh = 0;
  EXPECT_EQ(error_of(k), "test::Knobs::refresh = 0: must be >= 1");
  k.refresh = 1;
  k.safety = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error_of(k).rfind("sec.knobs.safety = ", 0), 0u) << error_of(k);
}

}  // namespace
