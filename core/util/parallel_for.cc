#include "core/util/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace tessera {

namespace {

std::atomic<unsigned> chosenThreads{0};

}  // namespace

unsigned workThreads() {
  const unsigned chosen = chosenThreads.load(std::memory_order_relaxed);
  return chosen > 0 ? chosen : std::clamp(std::thread::hardware_concurrency(), 1u, 4u);
}

void setWorkThreads(unsigned threads) {
  chosenThreads.store(threads, std::memory_order_relaxed);
}

void parallelFor(size_t n, unsigned threads, const std::function<void(size_t)>& body) {
  const size_t used = std::min<size_t>(n, threads);
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t i = next.fetch_add(1, std::memory_order_relaxed); i < n;
         i = next.fetch_add(1, std::memory_order_relaxed))
      body(i);
  };
  {
    std::vector<std::jthread> helpers;
    for (size_t t = 1; t < used; ++t) helpers.emplace_back(work);
    work();
  }  // the helpers join here
}

}  // namespace tessera
