// Modified Butterfly refinement (interpolating, 1-to-4 like Loop) on a
// level of triangles (core/topology/level.h): vertices keep their positions,
// each edge gains a point from butterfly_masks.h. Boundaries follow
// OpenMesh's ModifiedButterflyT: a boundary edge takes the 4-point rule; an
// interior edge uses the 8-point stencil when neither end is an interior
// vertex of valence other than 6, wing tips missing across a boundary being
// reflected (x + b - a); otherwise the stencils of its irregular interior
// ends, averaged.
#pragma once

#include <span>
#include <vector>

#include "core/loop/level_builder.h"
#include "core/mesh/surface_mesh.h"
#include "core/topology/level.h"
#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera::schemes {

// `childPoints` holds parent.numVertices + parent.numEdges() points.
void interpolateButterfly(const Level& parent, std::span<const Vec3> parentPoints,
                          std::span<Vec3> childPoints);

// Levels 0..levels of topology (Loop numbering) and the finest points.
struct TriangleRefinement {
  std::vector<Level> levels;
  std::vector<Vec3> points;
  SurfaceMesh surface() const;  // the finest level's triangles and points
};

// Sharpness tags are ignored: the Butterfly has no crease rules.
Expected<TriangleRefinement> refineButterfly(const BaseTopology& topology, std::span<const Vec3> points,
                                             int levels, long long maxFaces = 16LL * 1024 * 1024);

}  // namespace tessera::schemes
