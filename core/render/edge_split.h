// One edge of dynamic refinement (Kähler, Haber & Seidel, "Dynamic
// Refinement of Deformable Triangle Meshes for Rendering" §4.1-§4.2): how
// many times it is split, and where its new points go.
//
// Crack-freedom: the two triangles on an edge must agree on both, even when
// they sit in separately streamed regions. So everything here is a pure
// function of what both sides have -- the two end positions, which decode
// bit-identically on both sides (one quantization grid per document), and
// the normals at the ends -- evaluated in a canonical order (ends by the
// bits of their positions, sides by the bits of their normals). Asking from
// either end, or from either side, gives bit-identical points.
//
// At a crease the two sides have different normals at the same positions
// (the tessellation gives each sector its own, tessellation.h). Both sets
// of normals are then inputs: `other` holds the far side's, which a region
// learns from its neighbour through BorderEdges (dynamic_refinement.h).
#pragma once

#include <array>
#include <optional>

#include "core/util/vec3.h"

namespace tessera {

// The normals one adjacent triangle has at the edge's two ends.
struct EdgeSide {
  Vec3 n0, n1;
};

// The split criterion of the paper's §4.1 with fixed thresholds: the paper compares
// the endpoint normals' dot product with its value on the undeformed mesh;
// a streamed LOD has no undeformed state, and the bending it leaves is what
// refinement should remove, so the thresholds are absolute.
struct SplitCriterion {
  int maxSplits = 2;                // 0, 1 or 2
  double splitOnceBelow = 0.9994;   // cos 2 degrees
  double splitTwiceBelow = 0.9945;  // cos 6 degrees
};

struct EdgeSplit {
  int splits = 0;  // 0, 1 or 2
  // The points at 1/4, 1/2 and 3/4 of the way from p0 to p1 (only the
  // middle one when splits == 1; none when 0), with their normals on each side.
  std::array<Vec3, 3> points{};
  std::array<Vec3, 3> normals{};       // for `side`
  std::array<Vec3, 3> otherNormals{};  // for `other` (equal to normals without one)
};

// The edge p0 -> p1 as the triangle holding `side` sees it; `other` is the
// triangle across it, if any, with its normals at p0 and p1.
EdgeSplit splitEdge(const Vec3& p0, const Vec3& p1, const EdgeSide& side,
                    const std::optional<EdgeSide>& other, const SplitCriterion& criterion);

// Strict total order on the bits of a position (then used to orient edges).
bool bitsLess(const Vec3& a, const Vec3& b);
bool bitsEqual(const Vec3& a, const Vec3& b);

}  // namespace tessera
