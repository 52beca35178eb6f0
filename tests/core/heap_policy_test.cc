// The heap policy (core/util/heap_policy.h): after keepFreedMemoryForReuse,
// a block of 8 MiB comes from the heap rather than a mapping of its own, and
// once freed it stays in the process, free for the next allocation, until
// the heap is trimmed on purpose.
#include <malloc.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#include "core/util/heap_policy.h"

namespace tessera {
namespace {

TEST(HeapPolicy, FreedBlocksOfMegabytesStayInTheHeapForReuse) {
  ASSERT_TRUE(keepFreedMemoryForReuse());
  constexpr size_t kBytes = size_t{8} << 20;
  const struct mallinfo2 before = ::mallinfo2();
  void* block = std::malloc(kBytes);
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, kBytes);
  const struct mallinfo2 held = ::mallinfo2();
  EXPECT_EQ(held.hblks, before.hblks) << "the block has a mapping of its own";
  std::free(block);
  const struct mallinfo2 after = ::mallinfo2();
  EXPECT_GE(after.fordblks, kBytes) << "the freed block went back to the kernel";
  ::malloc_trim(0);  // what the server does after bulk work: now it goes back
  EXPECT_LT(::mallinfo2().fordblks, after.fordblks);
}

}  // namespace
}  // namespace tessera
