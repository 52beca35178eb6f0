// Canonical, stable identifiers for every vertex, edge and face of every
// subdivision level (docs/PROTOCOL.md §3.1, docs/DOCUMENT_FORMAT.md "Ids and
// frames").
//
// An id is (level, index) where index is the element's number in the
// *uniform* refinement of the base mesh (see core/loop/refinement.h):
//   vertex v of level l       -> vertex v of level l+1       (same index)
//   edge e of level l         -> vertex V_l + e of level l+1
//   edge e of level l         -> edges 2e, 2e+1 of level l+1 (halves)
//   face f of level l         -> faces 4f..4f+3, edges 2E_l + 3f + j
// The numbering depends only on the base mesh, never on which parts of the
// hierarchy happen to be built or in which order, so the same vertex reached
// from any base face has the same id in every process and after a restart.
//
// Packed into 64 bits (6 bits of level, 58 of index) and printed "v3:1234",
// "e2:55", "f4:1023".
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/util/status.h"

namespace tessera {

inline constexpr int kMaxIdLevel = 63;

template <char kKind>
class ElementId {
 public:
  static constexpr uint64_t kIndexBits = 58;
  static constexpr uint64_t kIndexMask = (uint64_t{1} << kIndexBits) - 1;

  constexpr ElementId() = default;
  constexpr ElementId(int level, uint64_t index)
      : packed_((static_cast<uint64_t>(level) << kIndexBits) | (index & kIndexMask)) {}

  constexpr int level() const { return static_cast<int>(packed_ >> kIndexBits); }
  constexpr uint64_t index() const { return packed_ & kIndexMask; }
  constexpr uint64_t packed() const { return packed_; }
  static constexpr ElementId fromPacked(uint64_t packed) {
    ElementId id;
    id.packed_ = packed;
    return id;
  }

  std::string toString() const {
    return std::string(1, kKind) + std::to_string(level()) + ":" + std::to_string(index());
  }

  friend constexpr bool operator==(ElementId a, ElementId b) { return a.packed_ == b.packed_; }
  friend constexpr auto operator<=>(ElementId a, ElementId b) { return a.packed_ <=> b.packed_; }

 private:
  uint64_t packed_ = 0;
};

using VertexId = ElementId<'v'>;
using EdgeId = ElementId<'e'>;
using FaceId = ElementId<'f'>;

// Parses "v3:1234" (and 'e', 'f' forms); errors name the text and the reason.
Expected<VertexId> parseVertexId(const std::string& text);
Expected<EdgeId> parseEdgeId(const std::string& text);
Expected<FaceId> parseFaceId(const std::string& text);

// Element counts of the uniform refinement at each level, from the base
// counts: V' = V + E, E' = 2E + 3F, F' = 4F. Knowing them makes parent and
// child relations pure arithmetic, and validates ids.
class LevelCounts {
 public:
  LevelCounts(uint64_t vertices, uint64_t edges, uint64_t faces, int maxLevel);

  int maxLevel() const { return static_cast<int>(counts_.size()) - 1; }
  uint64_t vertices(int level) const { return counts_[level][0]; }
  uint64_t edges(int level) const { return counts_[level][1]; }
  uint64_t faces(int level) const { return counts_[level][2]; }

  // Ok if the id's level is within the hierarchy and its index exists there.
  Status check(VertexId id) const;
  Status check(EdgeId id) const;
  Status check(FaceId id) const;

  // The level-0 vertex a vertex descends from unchanged, or the parent edge
  // that created it (level > 0 only).
  bool isVertexChild(VertexId id) const { return id.index() < vertices(id.level() - 1); }
  VertexId parentVertex(VertexId id) const { return {id.level() - 1, id.index()}; }
  EdgeId parentEdge(VertexId id) const { return {id.level() - 1, id.index() - vertices(id.level() - 1)}; }
  // The level at which a vertex first exists (0 for base vertices).
  int birthLevel(VertexId id) const;

  VertexId childOf(VertexId id) const { return {id.level() + 1, id.index()}; }
  VertexId childOf(EdgeId id) const { return {id.level() + 1, vertices(id.level()) + id.index()}; }
  FaceId parentFace(FaceId id) const { return {id.level() - 1, id.index() / 4}; }
  FaceId childFace(FaceId id, int k) const {
    return {id.level() + 1, 4 * id.index() + static_cast<uint64_t>(k)};
  }
  FaceId baseFace(FaceId id) const { return {0, id.index() >> (2 * id.level())}; }

 private:
  std::vector<std::array<uint64_t, 3>> counts_;
};

}  // namespace tessera

template <char kKind>
struct std::hash<tessera::ElementId<kKind>> {
  size_t operator()(tessera::ElementId<kKind> id) const noexcept {
    return std::hash<uint64_t>{}(id.packed());
  }
};
