// Buffer's large blocks (core/util/large_allocation.h): from 4 MiB up they
// start on a 2 MiB boundary, the size of a huge page, and hold what is
// written to them through growth and copies; smaller blocks are ordinary.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

#include "core/util/buffer.h"
#include "core/util/large_allocation.h"

namespace tessera {
namespace {

constexpr uintptr_t kTwoMiB = uintptr_t{2} << 20;

uintptr_t addressOf(const void* p) {
  return reinterpret_cast<uintptr_t>(p);
}

TEST(LargeAllocation, LargeBuffersStartOnAHugePageBoundary) {
  Buffer<int32_t> large(kLargeAllocationBytes / sizeof(int32_t) + 17);
  EXPECT_EQ(addressOf(large.data()) % kTwoMiB, 0u);
  std::iota(large.begin(), large.end(), 0);
  // Growth moves the contents into another large block.
  large.resize(3 * large.size());
  EXPECT_EQ(addressOf(large.data()) % kTwoMiB, 0u);
  EXPECT_EQ(large[12345], 12345);
  EXPECT_EQ(large[kLargeAllocationBytes / sizeof(int32_t) + 16],
            static_cast<int32_t>(kLargeAllocationBytes / sizeof(int32_t) + 16));
  Buffer<int32_t> copy = large;
  EXPECT_EQ(addressOf(copy.data()) % kTwoMiB, 0u);
  EXPECT_EQ(copy[777777], 777777);
}

TEST(LargeAllocation, TheBlockIsWholeHugePagesAndWritableToItsEnd) {
  const size_t bytes = kLargeAllocationBytes + 1;
  auto* block = static_cast<unsigned char*>(allocateLarge(bytes));
  ASSERT_NE(block, nullptr);
  EXPECT_EQ(addressOf(block) % kTwoMiB, 0u);
  block[0] = 1;
  block[bytes - 1] = 2;
  // Rounded up to whole huge pages: the rest of the last one is the block's.
  block[6 * (size_t{1} << 20) - 1] = 3;
  EXPECT_EQ(block[0] + block[bytes - 1] + block[6 * (size_t{1} << 20) - 1], 6);
  freeLarge(block);
}

TEST(LargeAllocation, SmallBuffersAreOrdinary) {
  // Below the threshold the block comes from the heap: 2 MiB alignment of
  // a small block would be chance, and several in a row all aligned is not.
  int aligned = 0;
  std::vector<Buffer<int32_t>> small;
  for (int i = 0; i < 8; ++i) {
    small.emplace_back(1000);
    aligned += addressOf(small.back().data()) % kTwoMiB == 0 ? 1 : 0;
  }
  EXPECT_LT(aligned, 8);
}

}  // namespace
}  // namespace tessera
