// The process's heap policy: freed memory kept for reuse instead of handed back to the system.
#pragma once

namespace common {

/// glibc's malloc hands freed memory back to the system as soon as more than 128 KiB lie free
/// at the top of a heap, and serves every block of 128 KiB or more with a fresh mapping that it
/// unmaps when freed. A DEM RVE rebuilds its neighbour list into fresh arrays and frees the old
/// ones, a migration serialises states of a megabyte: with the default policy each of them
/// touches fresh pages, and a fresh page costs a page fault (11 us on a virtual machine measured
/// here, 70 % of a 1000-sphere list build). Keeps up to `trim_bytes` free at a heap's top and
/// maps fresh only blocks of `mmap_bytes` (at most 32 MiB, glibc's own limit) or more. The peak
/// of the process's memory is unchanged (trimming only lowers it after a peak); what it holds
/// after a peak may stay up to `trim_bytes` per heap above what it uses (32 MiB kept too little
/// for the 8 x 16 biaxial's churn: as many page faults as glibc's default). Returns false where
/// the C library refused a setting (another libc: nothing changes).
bool keep_freed_memory(int trim_bytes = 256 << 20, int mmap_bytes = 32 << 20);

}  // namespace common
