// farm::kMeasureFields, the one table of the RVEs' grain-scale measures: its rows tile
// MicroMeasures exactly, and results.h5 and the points' Xdmf view are made from it (a measure
// added to the table appears in both with its unit and description).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "farm/micro_model.hpp"
#include "farm/results.hpp"
#include "farm/results_layout.hpp"

namespace {

// The rows, by offset, follow each other without gap or overlap from the first byte to the last.
TEST(MeasureFields, RowsTileMicroMeasures) {
  std::vector<farm::MeasureField> rows(std::begin(farm::kMeasureFields),
                                       std::end(farm::kMeasureFields));
  std::sort(rows.begin(), rows.end(),
            [](const auto& a, const auto& b) { return a.offset < b.offset; });
  std::size_t next = 0;
  for (const farm::MeasureField& f : rows) {
    EXPECT_EQ(f.offset, next) << f.name;
    EXPECT_TRUE(f.components == 1 || f.components == 3 || f.components == 9) << f.name;
    EXPECT_FALSE(std::string(f.unit).empty()) << f.name;
    EXPECT_FALSE(std::string(f.description).empty()) << f.name;
    next = f.offset + sizeof(double) * static_cast<std::size_t>(f.components);
  }
  EXPECT_EQ(next, sizeof(farm::MicroMeasures));
}

// values() reads and writes the member its row names; none() sets every double to NaN.
TEST(MeasureFields, ValuesAreTheMembers) {
  farm::MicroMeasures m;
  m.fabric[8] = 0.5;
  m.z_mech = 4.5;
  m.kinetic = 2e-9;
  for (const farm::MeasureField& f : farm::kMeasureFields) {
    const std::span<const double> v = farm::values(std::as_const(m), f);
    const std::string name = f.name;
    const double expected = name == "fabric" ? 0.5 : name == "z_mech" ? 4.5 : 2e-9;
    const double got = name == "fabric" ? v[8] : v[0];
    if (name != "unbalanced") {
      EXPECT_EQ(got, expected) << name;
    }
  }
  const farm::MicroMeasures none = farm::MicroMeasures::none();
  const auto* d = reinterpret_cast<const double*>(&none);
  for (std::size_t i = 0; i < farm::measure_doubles(); ++i) EXPECT_TRUE(std::isnan(d[i])) << i;
}

// results.h5 creates /rve/<name> for every row, after /means/q, with the row's unit and
// description, and nothing else under /rve that the table does not name besides the RVE series.
TEST(MeasureFields, EveryRowIsAResultsSeries) {
  const auto series = farm::results_detail::series();
  for (const farm::MeasureField& f : farm::kMeasureFields) {
    const std::string name = std::string("rve/") + f.name;
    const auto it = std::find_if(series.begin(), series.end(),
                                 [&](const farm::SeriesSpec& s) { return name == s.name; });
    ASSERT_NE(it, series.end()) << name;
    EXPECT_EQ(it->per_item, f.components);
    EXPECT_EQ(it->over, 'r');
    EXPECT_STREQ(it->unit, f.unit);
    EXPECT_STREQ(it->description, f.description);
    EXPECT_TRUE(farm::results_detail::added_later(name)) << name;
  }
}

}  // namespace
