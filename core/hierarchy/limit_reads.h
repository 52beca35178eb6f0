// Which vertices the limit of a complete vertex reads, for the hierarchy's
// incremental update (sparse_update.cc) and its record of what edits reach
// (SparseHierarchy::isReachedByEdit): the vertex and its ring under Loop's
// masks (core/loop/limit.h); under Catmull-Clark's (core/catmark/limit.h)
// also the far corners of its ring faces.
#pragma once

#include "core/topology/level.h"

namespace tessera {

// Whether `read(u)` holds for a vertex u the limit of complete vertex v reads.
template <typename Read>
inline bool limitReadsAny(const Level& m, Index v, bool quads, Read&& read) {
  if (read(v)) return true;
  if (!quads) {
    for (Index u : m.ringVerticesOf(v)) {
      if (read(u)) return true;
    }
    return false;
  }
  for (Index f : m.ringFacesOf(v)) {
    if (f < 0) continue;
    for (Index u : m.faceVerticesOf(f)) {
      if (read(u)) return true;
    }
  }
  return false;
}

}  // namespace tessera
