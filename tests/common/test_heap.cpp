// common::keep_freed_memory: a block freed and asked for again comes back without fresh pages.
#include "common/heap.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstddef>
#include <vector>

namespace {

long minor_faults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

}  // namespace

// 8 MiB touched, freed, and asked for again: under glibc's default policy the first block is a
// mapping of its own (unmapped when freed) and the second grows the heap into fresh pages, 2048
// page faults; kept, the second reuses the first's pages.
TEST(Heap, FreedMemoryIsReusedWithoutFreshPages) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "the address sanitizer's allocator replaces glibc's: its policy is its own";
#endif
  ASSERT_TRUE(common::keep_freed_memory());
  const std::size_t bytes = std::size_t{8} << 20;
  { const std::vector<char> a(bytes, 1); }
  const long before = minor_faults();
  {
    const std::vector<char> b(bytes, 2);
    EXPECT_EQ(b[bytes / 2], 2);
  }
  const long fresh = minor_faults() - before;
  EXPECT_LT(fresh, 64) << "8 MiB asked for again took " << fresh << " page faults (of 2048 pages)";
}
