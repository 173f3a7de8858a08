// The process's heap policy (see header).
#include "common/heap.hpp"

#if __has_include(<malloc.h>)
#include <malloc.h>  // defines __GLIBC__ (through features.h) where the C library is glibc
#endif

namespace common {

bool keep_freed_memory(int trim_bytes, int mmap_bytes) {
#if defined(__GLIBC__) && defined(M_TRIM_THRESHOLD) && defined(M_MMAP_THRESHOLD)
  // Setting either disables glibc's dynamic thresholds (which would otherwise move them back).
  const bool trim = mallopt(M_TRIM_THRESHOLD, trim_bytes) == 1;
  const bool mmap = mallopt(M_MMAP_THRESHOLD, mmap_bytes) == 1;
  return trim && mmap;
#else
  (void)trim_bytes;
  (void)mmap_bytes;
  return false;
#endif
}

}  // namespace common
