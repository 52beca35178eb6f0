// The exact limit of one non-smooth vertex as three masks over its ring at
// the level: position, and the two tangents whose cross product is the
// primary sector's normal (limit.h numbers the sectors).
//
// Everything exact_limit.cc does for a vertex before it reads a point (the
// stationary masks of limit_masks.h, the decay of semi-sharp features of
// decay_matrix.h, the choice of the primary sector) depends only on the
// sharpness of the vertex and its ring edges, its valence, rule and
// boundary. A per-thread cache keyed by exactly those values lets
// computeLimit evaluate a crease, corner, dart or semi-sharp vertex with
// one lookup and three dot products, as OpenSubdiv's Limit() does with its
// approximate masks (docs/LIMITS.md "Speed": exact limits no slower than
// Limit()).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/topology/level.h"

namespace tessera {

// Rings up to this valence have a key; larger ones (rare) take the general
// path in exact_limit.cc.
inline constexpr int kMaxStencilValence = 14;
inline constexpr size_t kLimitStencilCacheEntries = 8192;

struct LimitStencilKey {
  uint32_t header = 0;  // valence (low 16 bits), boundary, rule
  float vertexSharpness = 0.0f;
  std::array<float, kMaxStencilValence> edgeSharpness;  // ring order; only the first `valence` are read

  int valence() const { return static_cast<int>(header & 0xffffu); }
  // Bit for bit over the words in use, so that equal keys hash equally
  // (+0 and -0 differ) and the unused tail never needs clearing.
  bool operator==(const LimitStencilKey& other) const {
    return header == other.header &&
           std::memcmp(&vertexSharpness, &other.vertexSharpness, 4 * (1 + valence())) == 0;
  }
};

struct LimitStencil {
  // Weights over (vertex, ring 0 .. valence-1) of the level.
  std::vector<double> position, tangent1, tangent2;
};

// The key of v at this level under uniform decay; false when the ring is
// too large for a key (Chaikin decay also reads the far rings, so it has
// none either: the caller checks the method).
bool limitStencilKey(const Level& level, Index v, LimitStencilKey& key);

// The thread's cache. find() is nullptr on a miss; insert() refuses (and
// returns nullptr) past kLimitStencilCacheEntries, so distinct sharpness
// values cost time, never unbounded memory.
const LimitStencil* findLimitStencil(const LimitStencilKey& key);
const LimitStencil* insertLimitStencil(const LimitStencilKey& key, LimitStencil stencil);

}  // namespace tessera
