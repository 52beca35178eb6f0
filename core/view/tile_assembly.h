// Closing the cracks between tiles shown at different levels, on the
// receiving side (docs/VIEWS.md "Assembling tiles"): seed
// 000's method (Pulli & Lounsbery, "Hierarchical Editing and Rendering of
// Subdivision Surfaces" §3.2.2), the finer side's vertices moved onto the
// coarser side's edge. Tiles stay independent of their neighbours' levels,
// so each is encoded once and shared by every viewer; the receiver, which
// knows which tiles it shows, does the rest.
//
// Vertices are matched across tiles by id (the same id is the same limit
// point, bit for bit, in every tile). Along each boundary loop of a tile,
// a run of vertices that no other shown tile has, between two that one
// other tile has and joins by an edge, lies on that tile's coarser edge:
// each is put on the segment at its place along the run (the run has 2^k
// edges, so the places are the dyadic points a finer level would put
// there). A vertex on the surface's own boundary has no such neighbour and
// stays.
//
// Only a tile's boundary takes part: an edge two tiles share is on both
// boundaries, and a vertex another tile has is on both. So each tile's
// boundary is summarised once (TileBoundary), kept by the receiver while it
// holds the tile, and closing the cracks of a whole view reads the
// summaries alone: a delta that changes a few tiles costs their boundaries,
// not every triangle shown.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "core/tessellation/region_codec.h"

namespace tessera {

// An edge by its two vertex ids, the lower first.
using IdEdge = std::pair<uint64_t, uint64_t>;
struct IdEdgeHash {
  size_t operator()(const IdEdge& e) const noexcept {
    return std::hash<uint64_t>()(e.first * 0x9E3779B97F4A7C15ull ^ e.second);
  }
};

struct TileBoundary {
  // Boundary edges (used by one triangle; crease sides split a vertex into
  // copies, which share the id) as a graph over vertex ids.
  std::unordered_map<uint64_t, std::vector<uint64_t>> next;
  // Every edge of the tile, boundary or not, whose two ends are boundary
  // vertices: whether the tile joins two of them by an edge.
  std::unordered_set<IdEdge, IdEdgeHash> chords;
  // A boundary vertex's position and its copies' local indices.
  std::unordered_map<uint64_t, Vec3> position;
  std::unordered_map<uint64_t, std::vector<uint32_t>> copies;
};

TileBoundary tileBoundary(const RegionMesh& tile);

// `tiles`: the meshes shown, and `boundaries` their summaries, in the same
// order. Returns, per tile, its positions with those on a coarser
// neighbour's edge moved there (the others unchanged), and counts the
// vertices moved in `moved` when not null.
std::vector<std::vector<Vec3>> closeCracks(const std::vector<const RegionMesh*>& tiles,
                                           const std::vector<const TileBoundary*>& boundaries,
                                           int64_t* moved = nullptr);
// The same, summarising every tile first.
std::vector<std::vector<Vec3>> closeCracks(const std::vector<const RegionMesh*>& tiles,
                                           int64_t* moved = nullptr);

}  // namespace tessera
