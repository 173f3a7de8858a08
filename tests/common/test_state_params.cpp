// common/state_params.hpp: the rows of a parameter or choice table in a state, each a field named
// by its key ('/' for a sub-table's dot), read back bit for bit; an older version's fields under
// their former names; values that cannot be refused naming the field.
#include "common/state_params.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "common/state_store.hpp"

namespace {

enum class Shade { pale, deep };
inline constexpr std::array<common::Named<Shade>, 2> kShadeNames{
    {{"pale", Shade::pale}, {"deep", Shade::deep}}};
inline constexpr std::array<common::Named<int>, 2> kCoatNames{{{"one", 1}, {"two", 2}}};

struct Knobs {
  double gain = 0.25;
  double twist_k = 1.0;
  std::int64_t count = 3;
  int small = 2;
  Shade shade = Shade::deep;
  int coats = -1;  // no name: "not set"
};

inline constexpr auto kKnobs =
    common::make_table<Knobs>("Knobs", "sec",
                              {{"gain_factor", &Knobs::gain, common::Unit::Dimensionless,
                                common::any(), common::Source::job_default, "g"},
                               {"twisting.stiffness", &Knobs::twist_k, common::Unit::Dimensionless,
                                common::any(), common::Source::job_default, "t"},
                               {"count", &Knobs::count, common::Unit::Dimensionless, common::any(),
                                common::Source::cpp_only, "n"},
                               {"small", &Knobs::small, common::Unit::Dimensionless, common::any(),
                                common::Source::job_default, "s"}});

inline constexpr common::ChoiceTable<Knobs, 2> kKnobChoices{
    "sec",
    {common::choice<&Knobs::shade, kShadeNames>("shade", "s"),
     common::choice<&Knobs::coats, kCoatNames>("coats", "c")}};

TEST(StateParams, RowsAreFieldsNamedByTheirKeysAndReadBackBitForBit) {
  EXPECT_EQ(common::state_field("p/", "twisting.stiffness"), "p/twisting/stiffness");
  Knobs k;
  k.gain = 0.1 + 0.2;  // not a short decimal
  k.twist_k = std::numeric_limits<double>::denorm_min();
  k.count = (std::int64_t{1} << 53) + 1;  // not a double
  k.small = -7;
  k.shade = Shade::pale;
  k.coats = 2;
  common::StateStore s;
  common::write_params(s, "p/", kKnobs, k);
  common::write_choices(s, "p/", kKnobChoices, k);
  EXPECT_EQ(s.read_f64("p/gain_factor"), std::vector<double>{k.gain});
  EXPECT_EQ(s.read_f64("p/twisting/stiffness"), std::vector<double>{k.twist_k});
  EXPECT_EQ(s.read_i64("p/count"), std::vector<std::int64_t>{k.count});
  EXPECT_EQ(s.read_i64("p/small"), std::vector<std::int64_t>{-7});
  EXPECT_EQ(s.read_i64("p/shade"), std::vector<std::int64_t>{0});  // the index of "pale"
  EXPECT_EQ(s.read_i64("p/coats"), std::vector<std::int64_t>{1});  // of "two"
  EXPECT_EQ(s.fields().size(), 6u);
  Knobs back;
  common::read_params(s, "p/", kKnobs, back, "test state");
  common::read_choices(s, "p/", kKnobChoices, back, "test state");
  EXPECT_EQ(back.gain, k.gain);
  EXPECT_EQ(back.twist_k, k.twist_k);
  EXPECT_EQ(back.count, k.count);
  EXPECT_EQ(back.small, k.small);
  EXPECT_EQ(back.shade, k.shade);
  EXPECT_EQ(back.coats, k.coats);
  // A member without a name is written as -1 and read back as "not set".
  common::StateStore unset;
  common::write_choices(unset, "p/", kKnobChoices, Knobs{});
  EXPECT_EQ(unset.read_i64("p/coats"), std::vector<std::int64_t>{-1});
  Knobs none;
  none.coats = 1;
  common::read_choices(unset, "p/", kKnobChoices, none, "test state");
  EXPECT_EQ(none.coats, 1);
}

TEST(StateParams, AnOlderVersionIsReadUnderItsFormerNames) {
  const common::FormerField former[] = {
      {"gain_factor", "gain"},
      {"count", "count"},
      {"count", "n"},            // a second former name, tried next
      {"small", "small", true},  // absent in some older states
  };
  common::StateStore s;
  common::write_scalar(s, "p/gain", 0.5);
  common::write_scalar(s, "p/twisting/stiffness", 4.0);  // not renamed: read under its key
  common::write_scalar(s, "p/n", std::int64_t{9});
  Knobs k;
  common::read_params(s, "p/", kKnobs, k, "test state", former);
  EXPECT_EQ(k.gain, 0.5);
  EXPECT_EQ(k.twist_k, 4.0);
  EXPECT_EQ(k.count, 9);
  EXPECT_EQ(k.small, 2);  // absent: kept
  // A field of then that is missing is named by its former name.
  common::StateStore no_gain;
  common::write_scalar(no_gain, "p/twisting/stiffness", 4.0);
  common::write_scalar(no_gain, "p/n", std::int64_t{9});
  try {
    common::read_params(no_gain, "p/", kKnobs, k, "test state", former);
    ADD_FAILURE() << "read a state without gain";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'p/gain'"), std::string::npos) << e.what();
  }
}

TEST(StateParams, ValuesThatCannotBeAreRefusedNamingTheField) {
  Knobs k;
  common::StateStore s;
  common::write_params(s, "p/", kKnobs, k);
  common::write_scalar(s, "p/shade", std::int64_t{2});
  common::write_scalar(s, "p/coats", std::int64_t{0});
  try {
    common::read_choices(s, "p/", kKnobChoices, k, "test state");
    ADD_FAILURE() << "read a choice index out of range";
  } catch (const common::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "test state: field 'p/shade' = 2: must be one of 0 (pale), 1 (deep)");
  }
  common::StateStore nan;
  common::write_scalar(nan, "p/gain_factor", std::numeric_limits<double>::quiet_NaN());
  try {
    common::read_params(nan, "p/", kKnobs, k, "test state");
    ADD_FAILURE() << "read a NaN";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("test state: field 'p/gain_factor' value 0"),
              std::string::npos)
        << e.what();
  }
  common::StateStore typed;  // an integer row written as a double
  common::write_params(typed, "p/", kKnobs, k);
  common::StateStore wrong;
  for (const auto& [n, f] : typed.fields()) {
    if (n == "p/count") continue;
    std::visit([&](const auto& v) { wrong.write(n, std::span(v.data(), v.size())); }, f);
  }
  common::write_scalar(wrong, "p/count", 3.0);
  EXPECT_THROW(common::read_params(wrong, "p/", kKnobs, k, "test state"), common::InputError);
}

}  // namespace
