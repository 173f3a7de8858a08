// Checkpoint checksum: see checksum.hpp.
#include "farm/checksum.hpp"

#include <cstdio>

namespace farm {

std::uint64_t hash_words(const void* data, std::size_t n, std::uint64_t first) {
  return checksum(std::span<const std::uint64_t>(static_cast<const std::uint64_t*>(data), n),
                  first);
}

std::string hex(std::uint64_t v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace farm
