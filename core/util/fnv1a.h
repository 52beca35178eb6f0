// FNV-1a, 64 bits (Fowler, Noll and Vo; offset basis 0xcbf29ce484222325,
// prime 0x100000001b3): the hash of triangles in a surface hash
// (core/tessellation/surface_hash.h) and of stored blobs.
#pragma once

#include <cstdint>
#include <string_view>

namespace tessera {

inline constexpr uint64_t kFnv1aOffsetBasis = 0xcbf29ce484222325ull;
inline constexpr uint64_t kFnv1aPrime = 0x100000001b3ull;

// One more byte into a running hash.
constexpr uint64_t fnv1aByte(uint64_t hash, uint8_t byte) {
  return (hash ^ byte) * kFnv1aPrime;
}

inline uint64_t fnv1a64(std::string_view bytes, uint64_t hash = kFnv1aOffsetBasis) {
  for (const unsigned char c : bytes) hash = fnv1aByte(hash, c);
  return hash;
}

}  // namespace tessera
