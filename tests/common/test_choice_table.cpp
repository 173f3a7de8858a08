// common::ChoiceTable: a setting that is a name out of a list; the names and their values written
// once, the default read from the member initializer, every name going to its value and back.
#include "common/choice_table.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <string>

namespace {

enum class Colour { red, green, blue };

inline constexpr std::array<common::Named<Colour>, 3> kColourNames{
    {{"red", Colour::red}, {"green", Colour::green}, {"blue", Colour::blue}}};
inline constexpr std::array<common::Named<bool>, 2> kSideNames{{{"left", false}, {"right", true}}};

inline constexpr std::array<common::Named<int>, 2> kCoatNames{{{"one", 1}, {"two", 2}}};

struct Paint {
  Colour colour = Colour::green;  // job default "green"
  bool right = false;             // job default "left"
  bool glossy = true;             // a TOML boolean, job default true
  int coats = -1;                 // no name: an optional key, absent leaves -1
};

inline constexpr common::ChoiceTable<Paint, 4> kPaint{
    "sec.paint",
    {common::choice<&Paint::colour, kColourNames>("colour", "c"),
     common::choice<&Paint::right, kSideNames>("side", "s"),
     common::flag<&Paint::glossy>("glossy", "g"),
     common::choice<&Paint::coats, kCoatNames>("coats", "n")}};

TEST(ChoiceTable, NamesAndValuesBothWays) {
  EXPECT_EQ(common::name_of(kColourNames, Colour::blue), "blue");
  EXPECT_EQ(common::value_of(kColourNames, "red"), Colour::red);
  EXPECT_FALSE(common::value_of(kColourNames, "Red").has_value());  // names are exact
  EXPECT_FALSE(common::value_of(kColourNames, "").has_value());
  EXPECT_EQ(common::names_list(kColourNames), "red, green, blue");
  EXPECT_EQ(common::name_of(kSideNames, true), "right");
}

TEST(ChoiceTable, RowsKeyNamesAndDefaultsFromTheMemberInitializers) {
  const auto* colour = kPaint.row("colour");
  ASSERT_NE(colour, nullptr);
  EXPECT_EQ(kPaint.name(*colour), "sec.paint.colour");
  ASSERT_EQ(colour->count, 3u);
  EXPECT_EQ(colour->names[0], "red");
  EXPECT_EQ(colour->names[2], "blue");
  EXPECT_EQ(colour->doc, "c");
  EXPECT_EQ(colour->default_name(), "green");
  const auto* side = kPaint.row("side");
  ASSERT_NE(side, nullptr);
  EXPECT_EQ(side->default_name(), "left");
  EXPECT_EQ(kPaint.row("shade"), nullptr);
}

TEST(ChoiceTable, EveryNameSetsItsValueAndReadsBack) {
  for (const auto& row : kPaint) {
    for (std::size_t i = 0; i < row.count; ++i) {
      Paint p;
      row.assign(p, i);
      EXPECT_EQ(row.name_in(p), row.names[i]) << row.key;
      EXPECT_EQ(row.find(row.names[i]), i) << row.key;
    }
    EXPECT_FALSE(row.find("none of them").has_value()) << row.key;
  }
  Paint p;
  kPaint.row("colour")->assign(p, 2);
  EXPECT_EQ(p.colour, Colour::blue);
  EXPECT_FALSE(p.right);  // the other member untouched
  kPaint.row("side")->assign(p, 1);
  EXPECT_TRUE(p.right);
}

// A flag row is a bool member the job writes as a TOML boolean: names "false" and "true".
TEST(ChoiceTable, AFlagRowIsABooleanNamedFalseAndTrue) {
  const auto* glossy = kPaint.row("glossy");
  ASSERT_NE(glossy, nullptr);
  EXPECT_TRUE(glossy->boolean);
  EXPECT_FALSE(kPaint.row("side")->boolean);  // a bool with names of its own is a string key
  ASSERT_EQ(glossy->count, 2u);
  EXPECT_EQ(glossy->names[0], "false");
  EXPECT_EQ(glossy->names[1], "true");
  EXPECT_EQ(glossy->default_name(), "true");
  EXPECT_TRUE(glossy->has_default());
  Paint p;
  glossy->assign(p, *glossy->find("false"));
  EXPECT_FALSE(p.glossy);
  EXPECT_EQ(glossy->name_in(p), "false");
}

// A member initializer without a name (-1: not set) has no default: the key is optional.
TEST(ChoiceTable, AnInitializerWithoutANameMakesTheKeyOptional) {
  const auto* coats = kPaint.row("coats");
  ASSERT_NE(coats, nullptr);
  EXPECT_FALSE(coats->has_default());
  EXPECT_EQ(coats->default_name(), "?");
  EXPECT_TRUE(kPaint.row("colour")->has_default());
  Paint p;
  coats->assign(p, *coats->find("two"));
  EXPECT_EQ(p.coats, 2);
}

TEST(ChoiceTable, AValueWithoutANameReadsAsAQuestionMark) {
  Paint p;
  p.colour = static_cast<Colour>(7);
  const auto* colour = kPaint.row("colour");
  EXPECT_EQ(colour->index_of(p), colour->count);
  EXPECT_EQ(colour->name_in(p), "?");
  EXPECT_EQ(common::name_of(kColourNames, p.colour), "?");
}

}  // namespace
