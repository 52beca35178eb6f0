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

// What names the vertices of one region's root face: a triangle of Loop's
// split, or a quad of the quad split (docs/PROTOCOL.md 6.2, "Quad lattice
// ids"; the first `sides` entries of each array are used).
struct RegionFrame {
  uint64_t face = 0;                     // packed FaceId of the root face (the region id)
  int sides = 3;                         // 3 or 4
  uint64_t firstChild = 0;               // quads: the root's first child face (4 x index below level 0)
  std::array<uint64_t, 4> corners{};     // canonical indices of its corner vertices, in the face's order
  std::array<uint64_t, 4> edges{};       // canonical indices of its edges: edge j joins corners j and j+1
  uint8_t forward = 0;                   // bit j: edge j runs from corner j to corner j+1
  std::array<uint64_t, 4> baseCounts{};  // vertices, edges and faces of the base mesh (and corners, quads)

  friend bool operator==(const RegionFrame&, const RegionFrame&) = default;
};

// The frame as region_codec.h stores it: the root face's level (u8) and
// index, (quads) the first child, corners, edges, directions (u8) and base
// counts, the numbers as LEB128 varints (a dozen bytes for a small mesh).
void writeFrame(ByteWriter& w, const RegionFrame& frame);
// Errors (parse errors naming the field): truncated or overlong numbers, a
// face level or index no face id has, direction bits beyond the sides, a
// quad's first child that is not 4 x its index below level 0.
Expected<RegionFrame> readFrame(ByteReader& r, int sides);

// The frame of a region whose root face the hierarchy holds. Unsupported for
// a base face of the quad split with other than four corners: such a region
// carries its ids as labels.
Expected<RegionFrame> regionFrame(const SparseHierarchy& h, const LevelCounts& counts, FaceId region);

// The lattice of a frame's face `depth` levels down. A triangle's: (u, v)
// with u + v <= 2^depth, corner 0 at (0, 0), corner 1 at (2^depth, 0),
// corner 2 at (0, 2^depth). A quad's: 0 <= u, v <= 2^depth, corners 0 to 3
// at (0, 0), (2^depth, 0), (2^depth, 2^depth) and (0, 2^depth). Errors: a depth outside [0, kMaxLatticeDepth]
// or beyond the deepest id level, counts that overflow the ids.
inline constexpr int kMaxLatticeDepth = 7;  // coordinates fit a byte

class RegionLattice {
 public:
  static Expected<RegionLattice> build(const RegionFrame& frame, int depth);

  int depth() const { return depth_; }
  int side() const { return 1 << depth_; }
  // The id (at its birth level) of lattice point (u, v); nothing outside
  // the face.
  std::optional<VertexId> idAt(int u, int v) const;
  // The lattice point of an id, if the face holds it.
  std::optional<std::array<int, 2>> pointOf(VertexId id) const;

 private:
  int depth_ = 0;
  int sides_ = 3;
  std::vector<uint64_t> ids_;  // packed, by (u, v) row-major over the square
  std::unordered_map<uint64_t, std::array<int, 2>> points_;
};

}  // namespace tessera
