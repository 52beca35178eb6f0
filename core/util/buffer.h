// Buffer<T>: a std::vector whose resize() leaves trivial elements
// uninitialised. Level arrays are always written in full right after they
// are sized, so zero-filling them first would only double the memory traffic
// of refinement. Large arrays go on huge pages (large_allocation.h).
#pragma once

#include <cstddef>
#include <memory>
#include <type_traits>
#include <vector>

#include "core/util/large_allocation.h"

namespace tessera {

template <typename T, typename Base = std::allocator<T>>
class DefaultInitAllocator : public Base {
 public:
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U, typename std::allocator_traits<Base>::template rebind_alloc<U>>;
  };
  using Base::Base;
  DefaultInitAllocator() = default;
  template <typename U, typename B>
  DefaultInitAllocator(const DefaultInitAllocator<U, B>& other) noexcept : Base(other) {}

  T* allocate(size_t n) {
    if (n * sizeof(T) >= kLargeAllocationBytes) return static_cast<T*>(allocateLarge(n * sizeof(T)));
    return std::allocator_traits<Base>::allocate(static_cast<Base&>(*this), n);
  }
  void deallocate(T* p, size_t n) noexcept {
    if (n * sizeof(T) >= kLargeAllocationBytes) return freeLarge(p);
    std::allocator_traits<Base>::deallocate(static_cast<Base&>(*this), p, n);
  }

  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;  // default-init: no zeroing for trivial types
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    std::allocator_traits<Base>::construct(static_cast<Base&>(*this), p, std::forward<Args>(args)...);
  }
};

template <typename T>
using Buffer = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace tessera
