// The normals each region has along its border edges (edges with one
// triangle in the region), so that a region refined on its own can see
// across a crease that a region border separates it from (Kähler,
// Haber & Seidel's refinement adapted; dynamic_refinement.h). Edges are
// keyed by the bits of their end positions, which decode identically in both regions.
//
// A flat open-addressing table: a frame records and looks up every border
// edge of thousands of small regions, and a node per edge cost more than
// the refinement itself.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/render/edge_split.h"

namespace tessera {

class BorderEdges {
 public:
  // Records the normals one triangle has at p0 and p1 on the edge p0 -> p1
  // (a side equal to one already recorded, or a third side, is dropped).
  void record(const Vec3& p0, const Vec3& p1, const EdgeSide& side);
  // The normals at p0 and p1 on the far side of the edge p0 -> p1 from a
  // triangle whose normals there are `mine`; none when every recorded side
  // has the same normals (a smooth edge) or nothing was recorded.
  std::optional<EdgeSide> other(const Vec3& p0, const Vec3& p1, const EdgeSide& mine) const;
  size_t size() const { return entries_.size(); }
  void reserve(size_t edges);

 private:
  struct Entry {
    std::array<uint64_t, 6> key{};   // end positions' bits, in canonical order
    std::array<EdgeSide, 2> side{};  // normals at the key's first and second end
    int count = 0;
  };
  // The slot holding `key`, or the empty slot where it would go.
  size_t find(const std::array<uint64_t, 6>& key) const;
  void grow();

  std::vector<Entry> entries_;
  std::vector<int32_t> slots_;  // index into entries_, -1 when empty; size a power of two
};

}  // namespace tessera
