// Vertex ids from a region's lattice (region_codec.h, "lattice ids"): every
// vertex a region shows is a vertex of the uniform refinement of the
// region's root face, so it is a point (u, v) of that face's triangular
// lattice at the profile's deepest level, and its canonical id follows from
// the face's corner and edge ids by the numbering rules of ids.h and
// refinement.h alone. A region can then carry two small lattice coordinates
// per vertex, which Draco predicts from its neighbours almost for free,
// instead of eight bytes of id; the receiver rebuilds the ids from a frame of
// nine numbers.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "core/hierarchy/ids.h"
#include "core/util/byte_io.h"
#include "core/util/status.h"

namespace tessera {

class SparseHierarchy;

// What names the vertices of one region's root face.
struct RegionFrame {
  uint64_t face = 0;                     // packed FaceId of the root face (the region id)
  std::array<uint64_t, 3> corners{};     // canonical indices of its corner vertices, in the face's order
  std::array<uint64_t, 3> edges{};       // canonical indices of its edges: edge j joins corners j and j+1
  uint8_t forward = 0;                   // bit j: edge j runs from corner j to corner j+1 (refinement.h)
  std::array<uint64_t, 3> baseCounts{};  // vertices, edges and faces of the base mesh

  friend bool operator==(const RegionFrame&, const RegionFrame&) = default;
};

// The frame as region_codec.h stores it: the root face's level (u8) and
// index, corners x 3, edges x 3, directions (u8) and base counts x 3, the
// numbers as LEB128 varints (a dozen bytes for a small mesh, 81 fixed).
void writeFrame(ByteWriter& w, const RegionFrame& frame);
// Errors (parse errors naming the field): truncated or overlong numbers, a
// face level or index no face id has.
Expected<RegionFrame> readFrame(ByteReader& r);

// The frame of a region whose root face the hierarchy holds.
Expected<RegionFrame> regionFrame(const SparseHierarchy& h, const LevelCounts& counts, FaceId region);

// The lattice of a frame's face `depth` levels down: (u, v) with u + v <=
// 2^depth, corner 0 at (0, 0), corner 1 at (2^depth, 0), corner 2 at
// (0, 2^depth). Errors: a depth outside [0, kMaxLatticeDepth] or beyond the
// deepest id level, counts that overflow the ids.
inline constexpr int kMaxLatticeDepth = 7;  // coordinates fit a byte

class RegionLattice {
 public:
  static Expected<RegionLattice> build(const RegionFrame& frame, int depth);

  int depth() const { return depth_; }
  int side() const { return 1 << depth_; }
  // The id (at its birth level) of lattice point (u, v); nothing outside
  // the triangle.
  std::optional<VertexId> idAt(int u, int v) const;
  // The lattice point of an id, if the face holds it.
  std::optional<std::array<int, 2>> pointOf(VertexId id) const;

 private:
  int depth_ = 0;
  std::vector<uint64_t> ids_;  // packed, by (u, v) row-major over the square
  std::unordered_map<uint64_t, std::array<int, 2>> points_;
};

}  // namespace tessera
