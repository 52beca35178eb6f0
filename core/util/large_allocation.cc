#include "core/util/large_allocation.h"

#include <sys/mman.h>

#include <cstdlib>
#include <new>

namespace tessera {

namespace {
constexpr size_t kHugePageBytes = size_t{2} << 20;
}

void* allocateLarge(size_t bytes) {
  const size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  void* block = std::aligned_alloc(kHugePageBytes, rounded);
  if (block == nullptr) throw std::bad_alloc();
  // Advice only: a kernel without transparent huge pages refuses it, and the
  // block is then an ordinary one.
  (void)madvise(block, rounded, MADV_HUGEPAGE);
  return block;
}

void freeLarge(void* block) noexcept {
  std::free(block);
}

}  // namespace tessera
