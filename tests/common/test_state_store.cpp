// Tests for common::StateStore: named fields, errors, exact byte round trip.
#include "common/state_store.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "common/errors.hpp"

using common::StateStore;

TEST(StateStore, WritesAndReadsNamedFields) {
  StateStore s;
  const std::vector<double> x{1.0, -2.5, std::numeric_limits<double>::denorm_min()};
  const std::vector<std::int64_t> ids{7, -3};
  s.write("spheres/x", std::span<const double>(x));
  s.write("spheres/id", std::span<const std::int64_t>(ids));
  EXPECT_EQ(s.read_f64("spheres/x"), x);
  EXPECT_EQ(s.read_i64("spheres/id"), ids);
  EXPECT_TRUE(s.has("spheres/x"));
  EXPECT_FALSE(s.has("spheres/y"));
}

TEST(StateStore, MissingOrMistypedFieldIsAnInputErrorNamingIt) {
  StateStore s;
  const std::vector<double> x{1.0};
  s.write("a", std::span<const double>(x));
  try {
    (void)s.read_f64("b");
    FAIL() << "no throw";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'b' is missing"), std::string::npos);
  }
  EXPECT_THROW((void)s.read_i64("a"), common::InputError);
}

TEST(StateStore, WritingAFieldTwiceIsABug) {
  StateStore s;
  const std::vector<double> x{1.0};
  s.write("a", std::span<const double>(x));
  EXPECT_THROW(s.write("a", std::span<const double>(x)), common::InternalError);
}

TEST(StateStore, SerializeRoundTripIsBitExact) {
  StateStore s;
  const std::vector<double> x{0.1, std::nan(""), -0.0, 1e300};
  const std::vector<std::int64_t> n{};
  s.write("z/x", std::span<const double>(x));
  s.write("a/empty", std::span<const std::int64_t>(n));
  const auto bytes = s.serialize();
  const auto t = StateStore::deserialize(bytes);
  const auto y = t.read_f64("z/x");
  ASSERT_EQ(y.size(), x.size());
  EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(double)), 0);
  EXPECT_TRUE(t.read_i64("a/empty").empty());
  EXPECT_EQ(t.serialize(), bytes);
}

TEST(StateStore, TruncatedBufferIsRefused) {
  StateStore s;
  const std::vector<double> x{1.0, 2.0};
  s.write("x", std::span<const double>(x));
  auto bytes = s.serialize();
  bytes.resize(bytes.size() - 3);
  EXPECT_THROW((void)StateStore::deserialize(bytes), common::InputError);
}
