// Tests of farm/checksum.hpp: the checkpoint checksum is fixed (old checkpoints stay readable),
// independent of how a dataset is split into blocks, and sensitive to position and bits.
#include "farm/checksum.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace {

std::vector<double> values() {
  std::vector<double> v(1000);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = 0.5 * static_cast<double>(i) - 7.25;
  return v;
}

}  // namespace

// Pinned values: a change of the function would make every stored checkpoint "damaged".
TEST(Checksum, PinnedValues) {
  EXPECT_EQ(farm::splitmix64(0), 0xe220a8397b1dcdafULL);
  const std::vector<std::int64_t> ids{0, 1, 2, 3};
  EXPECT_EQ(farm::hex(farm::checksum(std::span<const std::int64_t>(ids), 0)),
            "0xe42138fd0c00686b");  // computed independently (Python)
}

TEST(Checksum, IndependentOfTheSplitIntoBlocks) {
  const std::vector<double> v = values();
  const std::uint64_t whole = farm::checksum(std::span<const double>(v), 0);
  // Three ranks' pieces, out of order: [600, 1000), [0, 250), [250, 600).
  std::uint64_t sum = 0;
  for (const farm::Block b : {farm::Block{600, 400}, farm::Block{0, 250}, farm::Block{250, 350}}) {
    sum += farm::checksum(std::span<const farm::Block>(&b, 1), v.data() + b.offset);
  }
  EXPECT_EQ(sum, whole);
  // Two blocks of one rank, concatenated.
  const std::vector<farm::Block> two{{10, 5}, {500, 7}};
  std::vector<double> cat(v.begin() + 10, v.begin() + 15);
  cat.insert(cat.end(), v.begin() + 500, v.begin() + 507);
  std::uint64_t expect = farm::checksum(std::span<const double>(v.data() + 10, 5), 10) +
                         farm::checksum(std::span<const double>(v.data() + 500, 7), 500);
  EXPECT_EQ(farm::checksum(std::span<const farm::Block>(two), cat.data()), expect);
}

TEST(Checksum, SensitiveToPositionAndBits) {
  std::vector<double> v = values();
  const std::uint64_t h = farm::checksum(std::span<const double>(v), 0);
  EXPECT_NE(farm::checksum(std::span<const double>(v), 1), h);  // same words, other positions
  std::swap(v[3], v[4]);
  EXPECT_NE(farm::checksum(std::span<const double>(v), 0), h);
  std::swap(v[3], v[4]);
  v[999] = -v[999];  // one bit
  EXPECT_NE(farm::checksum(std::span<const double>(v), 0), h);
  const std::vector<double> zeros{0.0};
  const std::vector<double> negative_zero{-0.0};
  EXPECT_NE(farm::checksum(std::span<const double>(zeros), 0),
            farm::checksum(std::span<const double>(negative_zero), 0));
}
