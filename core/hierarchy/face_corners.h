// The corners of one face of a sparse level, visited one by one:
// a fixed triangle on a level of Loop's split, whose hot loops (the
// incremental update) pay for a general polygon's offsets and sizes
// (docs/PERFORMANCE.md "Catmull-Clark in the hierarchy"), any polygon on the
// quad split's levels.
#pragma once

#include "core/topology/level.h"

namespace tessera {

template <typename Visit>
inline void forEachFaceVertex(const Level& m, Index f, Visit&& visit) {
  if (m.regularFaceSize == 3) {
    for (Index u : m.triangleVertices(f)) visit(u);
    return;
  }
  for (Index u : m.faceVerticesOf(f)) visit(u);
}

}  // namespace tessera
