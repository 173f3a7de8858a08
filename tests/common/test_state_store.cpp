// Tests for common::StateStore: named fields, errors, exact byte round trip.
#include "common/state_store.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

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

// serialize() sizes its buffer before writing it: the buffer is exactly the bytes written (a
// wrong size count would leave capacity over or reallocate).
TEST(StateStore, SerializedBufferIsSizedExactly) {
  StateStore s;
  const std::vector<double> x(1000, 0.5);
  const std::vector<std::int64_t> n{1, 2, 3};
  s.write("contacts/force", std::span<const double>(x));
  s.write("k", std::span<const std::int64_t>(n));
  const auto bytes = s.serialize();
  EXPECT_EQ(bytes.size(), 8U + (8 + 14 + 1 + 8 + 8000) + (8 + 1 + 1 + 8 + 24));
  EXPECT_EQ(bytes.capacity(), bytes.size());
}

// A buffer that holds one field twice is malformed input, refused naming the field.
TEST(StateStore, BufferWithAFieldTwiceIsRefusedNamingIt) {
  StateStore s;
  const std::vector<double> x{1.0};
  s.write("a", std::span<const double>(x));
  auto bytes = s.serialize();
  std::uint64_t two = 2;
  std::memcpy(bytes.data(), &two, sizeof two);  // two fields, the second a copy of the first
  const std::vector<char> field(bytes.begin() + 8, bytes.end());
  bytes.insert(bytes.end(), field.begin(), field.end());
  try {
    (void)StateStore::deserialize(bytes);
    FAIL() << "a duplicated field was read";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("field 'a' twice"), std::string::npos) << e.what();
  }
}

// A named scalar is a field of one value; anything else is refused naming the field.
TEST(StateStore, NamedScalars) {
  StateStore s;
  common::write_scalar(s, "params/material/young", 7e7);
  common::write_scalar(s, "params/numerics/dt_refresh", std::int64_t{100});
  EXPECT_EQ(s.read_f64("params/material/young"), std::vector<double>{7e7});
  EXPECT_EQ(common::read_scalar_f64(s, "params/material/young"), 7e7);
  EXPECT_EQ(common::read_scalar_i64(s, "params/numerics/dt_refresh"), 100);
  const std::vector<double> two{1.0, 2.0};
  s.write("params/material", std::span<const double>(two));
  try {
    (void)common::read_scalar_f64(s, "params/material");
    ADD_FAILURE() << "a 2-value field was read as a scalar";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'params/material' has 2 values, expected 1"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW((void)common::read_scalar_i64(s, "params/material/young"), common::InputError);
  EXPECT_THROW((void)common::read_scalar_f64(s, "params/material/poisson"), common::InputError);
}
