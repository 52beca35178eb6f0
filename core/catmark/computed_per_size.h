// Masks computed once per neighbourhood size and kept for the process: the
// exact dart masks per valence (dart_masks.h) and the crease-side tangents
// per face count (crease_span_tangent.h). The limit loops read them for
// every vertex, so a size below kFastSizes is read without a lock once it
// is computed; larger sizes, which real meshes rarely hold, take the lock.
#pragma once

#include <array>
#include <atomic>
#include <map>
#include <memory>
#include <mutex>

namespace tessera::catmark {

template <class T>
class ComputedPerSize {
 public:
  using Compute = T (*)(int size);
  explicit ComputedPerSize(Compute compute) : compute_(compute) {}

  const T& operator()(int size) const {
    const bool fast = size >= 0 && size < kFastSizes;
    if (fast) {
      if (const T* kept = fast_[static_cast<size_t>(size)].load(std::memory_order_acquire)) return *kept;
    }
    const std::lock_guard lock(mutex_);
    auto& slot = computed_[size];
    if (!slot) slot = std::make_unique<const T>(compute_(size));
    if (fast) fast_[static_cast<size_t>(size)].store(slot.get(), std::memory_order_release);
    return *slot;
  }

 private:
  static constexpr int kFastSizes = 128;
  const Compute compute_;
  mutable std::mutex mutex_;
  mutable std::map<int, std::unique_ptr<const T>> computed_;  // entries never move or go
  mutable std::array<std::atomic<const T*>, kFastSizes> fast_{};
};

}  // namespace tessera::catmark
