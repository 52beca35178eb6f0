// Masks kept per size (core/catmark/computed_per_size.h): each size is
// computed once however many threads ask at once, below and above the sizes
// read without a lock, and every caller gets the same object.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "core/catmark/computed_per_size.h"

namespace tessera::catmark {
namespace {

std::atomic<int> computations{0};

std::vector<int> squares(int size) {
  ++computations;
  return std::vector<int>(static_cast<size_t>(size % 7 + 1), size * size);
}

TEST(ComputedPerSize, EachSizeIsComputedOnceAndSharedByEveryThread) {
  static const ComputedPerSize<std::vector<int>> computed(squares);
  constexpr int kSizes = 300;  // past the lock-free sizes
  std::vector<std::vector<const std::vector<int>*>> seen(8, std::vector<const std::vector<int>*>(kSizes));
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) {
    threads.emplace_back([&, t] {
      for (int round = 0; round < 3; ++round)
        for (int k = 0; k < kSizes; ++k) {
          const int size = (k * 37 + t * 11) % kSizes;
          seen[t][size] = &computed(size);
        }
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(computations.load(), kSizes);
  for (int size = 0; size < kSizes; ++size) {
    for (int t = 1; t < 8; ++t) ASSERT_EQ(seen[t][size], seen[0][size]) << "size " << size;
    EXPECT_EQ(seen[0][size]->front(), size * size);
  }
}

}  // namespace
}  // namespace tessera::catmark
