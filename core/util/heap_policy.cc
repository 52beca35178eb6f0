#include "core/util/heap_policy.h"

#include <malloc.h>

namespace tessera {

bool keepFreedMemoryForReuse() {
  constexpr int kMmapThreshold = 32 << 20;  // DEFAULT_MMAP_THRESHOLD_MAX on 64-bit glibc
  constexpr int kTrimThreshold = 1 << 30;
  const bool mmap = ::mallopt(M_MMAP_THRESHOLD, kMmapThreshold) == 1;
  const bool trim = ::mallopt(M_TRIM_THRESHOLD, kTrimThreshold) == 1;
  return mmap && trim;
}

}  // namespace tessera
