// Crack-free triangles for one leaf of a cut (Pulli & Lounsbery,
// "Hierarchical Editing and Rendering of Subdivision Surfaces" §3.2.2). A leaf
// next to finer neighbours collects, recursively, the finer vertices on its
// edges; it is then covered by a fan from the opposite corner when one edge
// has such vertices. When two or three do, it is first split at those
// edges' midpoints (which always exist there: a finer neighbour's first
// vertex on a shared edge is its midpoint), and each part is covered the
// same way -- the paper's two fans generalised so that no triangle ever
// has three points on one line of the parent triangle. No T-vertices, no
// degenerate triangles, and the leaf's orientation is kept. A quad leaf of
// Catmull-Clark's split is two triangles on its first diagonal; with finer
// points on its sides, a fan from a corner whose sides hold none, or else
// two quads split at the midpoints of two opposite sides, covered the same
// way, with the same guarantees.
#pragma once

#include <array>
#include <vector>

#include "core/hierarchy/sparse_hierarchy.h"
#include "core/tessellation/adaptive_cut.h"

namespace tessera {

struct VertexRef {
  int level;
  Index local;
};

using RefTriangle = std::array<VertexRef, 3>;

void triangulateLeaf(const SparseHierarchy& h, const AdaptiveCut& cut, int level, Index face,
                     std::vector<RefTriangle>& out);

// A face shown whole, with no finer point on its sides (a tile's faces,
// core/view/tile_builder.h): the triangle itself; a quad's two triangles on
// its first diagonal, corners 0, 1, 2 and 0, 2, 3, as a leaf's; a base
// n-gon's fan from its first corner.
void triangulateFace(const SparseHierarchy& h, int level, Index face, std::vector<RefTriangle>& out);

}  // namespace tessera
