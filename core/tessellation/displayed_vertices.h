// Where a displayed vertex's position and normal come from, the same for
// every tessellation of a document -- an adaptive cut's regions
// (tessellation.h) and a view's tiles at one level (tile_builder.h) -- so
// that a vertex shared by two of them decodes bit-identically in both: its
// limit at a level chosen from the document alone (the rule and its reasons
// are in tessellation.h), and the normal of the side of a crease or corner
// the triangle lies on.
#pragma once

#include <optional>
#include <vector>

#include "core/hierarchy/ids.h"
#include "core/hierarchy/sparse_hierarchy.h"
#include "core/tessellation/leaf_triangulation.h"
#include "core/tessellation/region_codec.h"

namespace tessera {

// The vertex and level `v`'s displayed limit is taken at; when the
// hierarchy does not hold the vertex's ring there, a face to grow it there
// is appended to `growth` and nothing is returned.
std::optional<VertexRef> limitSource(const SparseHierarchy& h, const LevelCounts& counts, VertexRef v,
                                     std::vector<FaceId>& growth);

// Triangles over hierarchy vertices (each with the leaf (level, face) it
// lies in) as a region's mesh: every vertex at its displayed limit, one per
// (vertex, side), with its id at its birth level. Triangles whose limits the
// hierarchy does not hold yet are left out, and `growth` says where to grow
// it (the caller grows and starts again).
RegionMesh meshOfTriangles(const SparseHierarchy& h, const LevelCounts& counts,
                           const std::vector<RefTriangle>& triangles, const std::vector<VertexRef>& leaves,
                           std::vector<FaceId>& growth);

}  // namespace tessera
