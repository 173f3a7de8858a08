// Unit tests of the farm's wire records (farm/exchange.hpp): sizes as docs/design/farm.md states them, and
// a record that survives the byte copy of the wire bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>

#include "common/tensor.hpp"
#include "farm/exchange.hpp"

namespace {

// The figures of docs/design/farm.md ("Protocol"): a 24-byte header, 160-byte records, 120-byte start-up
// records. A new field changes these sizes: update the docs with them.
TEST(Exchange, RecordSizesAreThoseTheDocsState) {
  EXPECT_EQ(sizeof(farm::CommandHeader), 24u);
  EXPECT_EQ(sizeof(farm::RveRecord), 160u);
  EXPECT_EQ(sizeof(farm::InitRecord), 120u);
  EXPECT_EQ(sizeof(farm::MicroReport), 64u);
  EXPECT_EQ(offsetof(farm::RveRecord, report), 72u);
  // Command::measure's record (output rows only): fabric 9 + z_mech, unbalanced, kinetic.
  EXPECT_EQ(sizeof(farm::MicroMeasures), 96u);
}

TEST(Exchange, MeasuresRoundTripThroughBytesBitForBit) {
  farm::MicroMeasures a;
  for (int i = 0; i < 9; ++i) a.fabric[i] = (i % 4 == 0) ? 1.0 / 3.0 : -0.0;
  a.fabric[1] = std::numeric_limits<double>::denorm_min();
  a.z_mech = 4.25;
  a.unbalanced = 1e-300;
  a.kinetic = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> wire(sizeof a / sizeof(double));
  std::memcpy(wire.data(), &a, sizeof a);
  farm::MicroMeasures b;
  b.kinetic = 0.0;
  std::memcpy(static_cast<void*>(&b), wire.data(), sizeof b);
  EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0);
  EXPECT_TRUE(std::signbit(b.fabric[2]));
  EXPECT_EQ(b.fabric[1], std::numeric_limits<double>::denorm_min());
  EXPECT_TRUE(std::isnan(b.kinetic));
  // A continuum model's measures: every entry NaN.
  const farm::MicroMeasures none = farm::MicroMeasures::none();
  for (const double f : none.fabric) EXPECT_TRUE(std::isnan(f));
  EXPECT_TRUE(std::isnan(none.z_mech) && std::isnan(none.unbalanced) && std::isnan(none.kinetic));
}

TEST(Exchange, RecordRoundTripsThroughBytesBitForBit) {
  farm::RveRecord a;
  common::Mat3 s;
  s << -1.0, 2.5e-300, -0.0, std::numeric_limits<double>::denorm_min(), 5.0, 6.0, 7.0, 8.0, -9.0;
  common::row_major_out(a.stress) = s;
  a.report.p = 1.0;
  a.report.q = 2.0;
  a.report.void_ratio = 0.6;
  a.report.z = 4.5;
  a.report.dem_steps = (std::int64_t{1} << 60) + 1;  // exact only as an integer, not as a double
  a.report.t_p = 1e-3;
  a.report.guards = 0xFFFFFFFFu;
  a.report.wall_s = 0.25;
  a.wave_speed = 336.0;
  a.cpu_s = 0.125;
  a.error = farm::ErrorKind::numerical;
  a.dilute = 1;
  std::vector<double> wire(sizeof a / sizeof(double));
  std::memcpy(wire.data(), &a, sizeof a);
  farm::RveRecord b;
  std::memcpy(static_cast<void*>(&b), wire.data(), sizeof b);
  const common::Mat3 t = common::row_major(b.stress);
  EXPECT_EQ(std::memcmp(s.data(), t.data(), sizeof(double) * 9), 0);
  EXPECT_TRUE(std::signbit(t(0, 2)));
  EXPECT_EQ(t(0, 1), s(0, 1));  // row-major: (0,1) is the second double
  EXPECT_EQ(b.stress[1], 2.5e-300);
  EXPECT_EQ(b.report.dem_steps, a.report.dem_steps);
  EXPECT_EQ(b.report.guards, a.report.guards);
  EXPECT_EQ(b.report.wall_s, a.report.wall_s);
  EXPECT_EQ(b.error, farm::ErrorKind::numerical);
  EXPECT_EQ(b.cpu_s, 0.125);
  EXPECT_EQ(b.dilute, 1);
}

}  // namespace
