// Checkpoint checksum: see checksum.hpp.
#include "farm/checksum.hpp"

#include <cstdio>

namespace farm {

std::string hex(std::uint64_t v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace farm
