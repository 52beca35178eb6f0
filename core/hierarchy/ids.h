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
#include <memory>
#include <span>
#include <string>
#include <utility>
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

// How each level splits its faces: Loop's 1-to-4 triangle split, or the
// quad split of Catmull-Clark (core/catmark/quad_split.h), where a base face
// of n corners has n children and every face below is a quad.
enum class SplitKind { kTriangles, kQuads };

// Element counts of the uniform refinement at each level, from the base
// counts. Triangles: V' = V + E, E' = 2E + 3F, F' = 4F. Quads: V' = V + F + E,
// E' = 2E + C, F' = C, with C the level's corners (the sum of its face
// sizes; 4F below the base). Knowing them makes parent and child relations
// pure arithmetic, and validates ids (docs/ARCHITECTURE.md "Numbering").
class LevelCounts {
 public:
  // Triangles, split by Loop's rules.
  LevelCounts(uint64_t vertices, uint64_t edges, uint64_t faces, int maxLevel);
  // Polygons, split into quads: base face f has faceSizes[f] corners.
  static LevelCounts quads(uint64_t vertices, uint64_t edges, std::span<const int> faceSizes, int maxLevel);

  SplitKind split() const { return split_; }
  bool quads() const { return split_ == SplitKind::kQuads; }
  int maxLevel() const { return static_cast<int>(counts_.size()) - 1; }
  uint64_t vertices(int level) const { return counts_[level][0]; }
  uint64_t edges(int level) const { return counts_[level][1]; }
  uint64_t faces(int level) const { return counts_[level][2]; }
  // The sum of the level's face sizes.
  uint64_t corners(int level) const { return counts_[level][3]; }

  // Ok if the id's level is within the hierarchy and its index exists there.
  Status check(VertexId id) const;
  Status check(EdgeId id) const;
  Status check(FaceId id) const;

  // Where a vertex of a level > 0 comes from: the child of a parent vertex
  // (same index), the vertex on a parent edge, or (quads) the vertex in a
  // parent face.
  enum class Origin { kVertex, kEdge, kFace };
  Origin originOf(VertexId id) const;
  bool isVertexChild(VertexId id) const { return id.index() < vertices(id.level() - 1); }
  VertexId parentVertex(VertexId id) const { return {id.level() - 1, id.index()}; }
  EdgeId parentEdge(VertexId id) const {
    return {id.level() - 1, id.index() - firstEdgeChild(id.level() - 1)};
  }
  FaceId parentFaceOfVertex(VertexId id) const {
    return {id.level() - 1, id.index() - vertices(id.level() - 1)};
  }
  // The level at which a vertex first exists (0 for base vertices).
  int birthLevel(VertexId id) const;

  VertexId childOf(VertexId id) const { return {id.level() + 1, id.index()}; }
  VertexId childOf(EdgeId id) const { return {id.level() + 1, firstEdgeChild(id.level()) + id.index()}; }
  // The vertex a quad split puts in face `id`.
  VertexId faceVertexOf(FaceId id) const { return {id.level() + 1, vertices(id.level()) + id.index()}; }
  // The index of face `id`'s first child face: 4f, or for a base face of
  // a quad split its first corner (its children are numbered by corner).
  // Under a quad split it is also the face's first interior child edge.
  uint64_t firstChildFace(FaceId id) const;
  int faceSize(FaceId id) const;
  FaceId parentFace(FaceId id) const;
  FaceId childFace(FaceId id, int k) const {
    return {id.level() + 1, firstChildFace(id) + static_cast<uint64_t>(k)};
  }
  FaceId baseFace(FaceId id) const;
  // The ancestor of face `id` at `level` (0 <= level <= id's level): the
  // face it lies in there.
  FaceId ancestorAt(FaceId id, int level) const;
  // The faces of `level` (>= id's level) inside face `id`: the indices
  // [first, second), contiguous under both splits.
  std::pair<uint64_t, uint64_t> descendantsAt(FaceId id, int level) const;

 private:
  // The index of the first vertex a split puts on an edge of `level`.
  uint64_t firstEdgeChild(int level) const { return vertices(level) + (quads() ? faces(level) : 0); }

  SplitKind split_ = SplitKind::kTriangles;
  // Quads: base face f's first corner, per face and one past the last.
  std::shared_ptr<const std::vector<uint64_t>> baseFaceBegin_;
  std::vector<std::array<uint64_t, 4>> counts_;  // vertices, edges, faces, corners
};

}  // namespace tessera

template <char kKind>
struct std::hash<tessera::ElementId<kKind>> {
  size_t operator()(tessera::ElementId<kKind> id) const noexcept {
    return std::hash<uint64_t>{}(id.packed());
  }
};
