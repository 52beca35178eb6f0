// Uniform 1-to-4 refinement of a Level's topology and sharpness.
//
// Child numbering: vertex v of the parent is child vertex v (so the first V0
// vertices of every level are the images of the input vertices, in order);
// the vertex on parent edge e is child vertex numVertices + e. Parent face f
// has children 4f+0..4f+2 at its corners 0..2 and 4f+3 in the middle. Child
// edges 2e and 2e+1 halve parent edge e at its ends 0 and 1; child edges
// 2E + 3f + j are interior to face f. The layout of faces, edges and rings
// matches OpenSubdiv's TriRefinement so that ring orders, and therefore
// limit tangents at creases and corners, agree.
#pragma once

#include "core/loop/level.h"
#include "core/loop/loop_options.h"

namespace tessera {

enum class RefineDetail {
  kFull,           // every relation: needed to refine further or evaluate limits
  kFacesOnly,      // faces, sharpness and rules only: enough to interpolate
                   // points into this level and draw it (OpenSubdiv's
                   // fullTopologyInLastLevel = false)
};

// The child of parent edge e that touches its end vertex `end` (2e or 2e+1).
inline Index childEdgeAtEnd(const Level& parent, Index e, Index end) {
  return 2 * e + (parent.edgeVertices[e][0] == end ? 0 : 1);
}

Level refineLevel(const Level& parent, const LoopOptions& options, RefineDetail detail = RefineDetail::kFull);

}  // namespace tessera
