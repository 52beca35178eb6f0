// Tags and the boundary rules on a built level (tags at level 0 only, as in
// OpenSubdiv's Far::TopologyRefinerFactory): crease sharpness on edges named
// by their two vertices, corner sharpness on vertices, then the rules of
// Sdc's prepareComponentTagsAndSharpness: boundary edges become infinitely
// sharp and, with kEdgeAndCorner, a boundary vertex with a single face
// becomes an infinitely sharp corner. Shared by every scheme.
#pragma once

#include <span>

#include "core/mesh/sharpness.h"
#include "core/topology/level.h"
#include "core/util/status.h"

namespace tessera::topology {

struct Crease {
  int v0, v1;
  float sharpness;
};

// The sharpness vertex v of `level` holds when tagged `tagged`: a
// topological corner (a boundary vertex with two edges) stays infinitely
// sharp under the edge-and-corner boundary rule, whatever its tag, as Sdc
// sharpens it (OpenSubdiv, Sdc::Options VTX_BOUNDARY_EDGE_AND_CORNER).
float heldVertexSharpness(const Level& level, Index v, float tagged, BoundaryInterpolation boundary);

// Sets edgeSharpness, vertexSharpness and vertexRules of `level`.
// vertexSharpness is empty or one value per vertex. Errors name the crease
// and the edge it names when a vertex is out of range or the edge does not
// exist.
Status applyTags(std::span<const Crease> creases, std::span<const float> vertexSharpness,
                 BoundaryInterpolation boundary, Level& level);

}  // namespace tessera::topology
