// Large arrays on transparent huge pages. A refined level's arrays run to
// tens of megabytes, and every fresh 4 KiB page costs the kernel a fault:
// perf on tessera_bench_loop (RefineFull, fandisk level 4) put about 70 % of
// the time in the kernel's page-fault path and 20 % in the refinement itself
// (docs/PERFORMANCE.md "One topology type for every scheme, and large arrays
// on huge pages"). Blocks of at least kLargeAllocationBytes are aligned to
// 2 MiB and advised MADV_HUGEPAGE, so where the kernel allows huge pages on
// request (the "madvise" setting of /sys/kernel/mm/transparent_hugepage/
// enabled, Debian's default) one fault maps 2 MiB. Where it does not, the
// advice is ignored and nothing changes.
#pragma once

#include <cstddef>

namespace tessera {

inline constexpr size_t kLargeAllocationBytes = size_t{4} << 20;

// At least `bytes` bytes (bytes >= kLargeAllocationBytes), 2 MiB aligned;
// throws std::bad_alloc like operator new when memory is exhausted.
void* allocateLarge(size_t bytes);
// Frees a block from allocateLarge.
void freeLarge(void* block) noexcept;

}  // namespace tessera
