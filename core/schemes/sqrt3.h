// Kobbelt's sqrt(3) refinement of closed triangle meshes. Child numbering:
// the parent's vertices first, then one vertex per parent face (nV + f).
// Each parent edge (a, b) with faces F (running a to b) and G becomes the two
// triangles (a, centre G, centre F) and (centre G, b, centre F): the split and
// the edge flip in one step.
//
// Meshes with a boundary are refused: Kobbelt's boundary rule (a 1-to-9 split
// of boundary edges every other step) is not implemented.
#pragma once

#include <span>
#include <vector>

#include "core/loop/level_builder.h"
#include "core/schemes/butterfly.h"
#include "core/topology/level.h"
#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera::schemes {

// `childPoints` holds parent.numVertices + parent.numFaces() points.
void interpolateSqrt3(const Level& parent, std::span<const Vec3> parentPoints, std::span<Vec3> childPoints);
// Triangles of the child level (numbering above).
std::vector<std::array<int, 3>> sqrt3ChildTriangles(const Level& parent);

// Sharpness tags are ignored: sqrt(3) has no crease rules here.
Expected<TriangleRefinement> refineSqrt3(const BaseTopology& topology, std::span<const Vec3> points,
                                         int levels, long long maxFaces = 16LL * 1024 * 1024);

// Limit positions of every vertex of a level (Kobbelt's limit mask).
std::vector<Vec3> sqrt3LimitPositions(const Level& level, std::span<const Vec3> points);

}  // namespace tessera::schemes
