// The checkpoint checksum: a position-keyed 64-bit sum over 8-byte words, additive so that ranks
// holding disjoint pieces of a dataset combine their partial sums with MPI_SUM, and independent
// of how the dataset is split into pieces (docs/reference/checkpoint.md, "Checksums").
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <string>

namespace farm {

/// One contiguous piece of a one-dimensional dataset: elements [offset, offset + count).
struct Block {
  std::uint64_t offset = 0;
  std::uint64_t count = 0;
};

/// SplitMix64 finaliser (Steele, Lea & Flood 2014): a bijective 64-bit mixer.
[[nodiscard]] constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27U)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31U);
}

/// sum_i splitmix64(w_i ^ splitmix64(first + i)) mod 2^64, w_i the element i zero-extended to 64
/// bits (its bytes, not its value: -0.0 and 0.0 differ).
template <class T>
[[nodiscard]] std::uint64_t checksum(std::span<const T> data, std::uint64_t first) {
  static_assert(sizeof(T) <= sizeof(std::uint64_t), "elements of at most 8 bytes");
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < data.size(); ++i) {
    std::uint64_t w = 0;
    std::memcpy(&w, &data[i], sizeof(T));
    sum += splitmix64(w ^ splitmix64(first + i));
  }
  return sum;
}

/// Partial checksum of `blocks` whose elements are concatenated in `data`.
template <class T>
[[nodiscard]] std::uint64_t checksum(std::span<const Block> blocks, const T* data) {
  std::uint64_t sum = 0;
  std::size_t pos = 0;
  for (const Block& b : blocks) {
    sum += checksum(std::span<const T>(data + pos, b.count), b.offset);
    pos += b.count;
  }
  return sum;
}

/// "0x" and 16 hex digits.
[[nodiscard]] std::string hex(std::uint64_t v);

}  // namespace farm
