// farm::kReportFields, the one table of the RVEs' per-step fields (MicroReport): every output
// member has its row, the row reads and writes that member, and results.h5 (/rve/<name>, and
// /points/<name> where the row has a point description) is made from it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <set>
#include <string>

#include "farm/exchange.hpp"
#include "farm/micro_model.hpp"
#include "farm/results.hpp"
#include "farm/results_layout.hpp"

namespace {

// Every member of MicroReport but the timing (wall_s) has one row, of its own type.
TEST(ReportFields, RowsNameEveryOutputMemberOfMicroReport) {
  const std::set<std::size_t> want{
      offsetof(farm::MicroReport, p),          offsetof(farm::MicroReport, q),
      offsetof(farm::MicroReport, void_ratio), offsetof(farm::MicroReport, z),
      offsetof(farm::MicroReport, dem_steps),  offsetof(farm::MicroReport, t_p),
      offsetof(farm::MicroReport, guards)};
  std::set<std::size_t> have;
  std::size_t state = 0;
  for (const farm::ReportField& f : farm::kReportFields) {
    EXPECT_TRUE(have.insert(f.offset).second) << f.name << ": two rows for one member";
    EXPECT_FALSE(std::string(f.description).empty()) << f.name;
    state += f.state ? 1 : 0;
  }
  EXPECT_EQ(have, want);
  EXPECT_EQ(state, farm::report_state_fields());
  EXPECT_EQ(sizeof(farm::InitRecord),
            (9 + farm::report_state_fields() + 2) * sizeof(double));  // stress, state, 2 more
}

// report_real / report_int / set_report_real read and write the member the row names.
TEST(ReportFields, ValuesAreTheMembers) {
  farm::MicroReport r;
  r.p = 1.5;
  r.q = 2.5;
  r.void_ratio = 0.6;
  r.z = 4.25;
  r.t_p = 3e-4;
  r.dem_steps = 123456789012;
  r.guards = 0x80000041u;
  for (const farm::ReportField& f : farm::kReportFields) {
    const std::string n = f.name;
    if (f.type == farm::ReportType::real) {
      const double want = n == "p"            ? 1.5
                          : n == "q"          ? 2.5
                          : n == "void_ratio" ? 0.6
                          : n == "z"          ? 4.25
                                              : 3e-4;
      EXPECT_EQ(farm::report_real(r, f), want) << n;
      farm::MicroReport w;
      farm::set_report_real(w, f, want);
      EXPECT_EQ(farm::report_real(w, f), want) << n;
    } else {
      EXPECT_EQ(farm::report_int(r, f), n == "dem_steps" ? 123456789012 : 0x80000041LL) << n;
    }
  }
}

// results.h5 creates /rve/<name> for every row (an integer dataset for the counts and bits) and
// /points/<name> for the rows with a point description, with the row's unit and descriptions.
TEST(ReportFields, EveryRowIsAResultsSeries) {
  const auto series = farm::results_detail::series();
  auto find = [&](const std::string& name) {
    return std::find_if(series.begin(), series.end(),
                        [&](const farm::SeriesSpec& s) { return name == s.name; });
  };
  for (const farm::ReportField& f : farm::kReportFields) {
    const auto rve = find(std::string("rve/") + f.name);
    ASSERT_NE(rve, series.end()) << f.name;
    EXPECT_EQ(rve->over, 'r');
    EXPECT_EQ(rve->integer, f.type != farm::ReportType::real) << f.name;
    EXPECT_STREQ(rve->unit, f.unit);
    EXPECT_STREQ(rve->description, f.description);
    const auto pt = find(std::string("points/") + f.name);
    if (f.point_description == nullptr) {
      EXPECT_EQ(pt, series.end()) << f.name;
      continue;
    }
    ASSERT_NE(pt, series.end()) << f.name;
    EXPECT_EQ(pt->over, 'p');
    EXPECT_STREQ(pt->description, f.point_description);
  }
}

}  // namespace
