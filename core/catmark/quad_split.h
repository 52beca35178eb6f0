// Quad splitting of a Level (Catmull-Clark and bilinear topology): a face
// of n corners becomes n quads around a new face vertex, every edge gains a
// vertex and two halves. Numbering and ring orders are OpenSubdiv's
// QuadRefinement with vertices from vertices first:
//   child vertices: [0, nV) from vertices, then one per face, then one per edge;
//   child faces:    child j of face f is faceBegin(f) + j (at corner j);
//   child edges:    faceBegin(f) + j joins face f's vertex to edge j's vertex,
//                   then 2 per parent edge e: corners + 2e + end joins e's
//                   vertex to the child of edgeVertices[e][end].
// Sharpness decays by the crease method (Sdc semantics, core/loop/crease.h).
#pragma once

#include "core/catmark/polygon_level.h"
#include "core/topology/level.h"

namespace tessera {

enum class SplitDetail {
  kFull,       // every relation: the level can be refined again, or limits taken
  kFacesOnly,  // faces, sharpness and rules: enough to interpolate into and draw
};

Level splitToQuads(const Level& parent, const CreaseOptions& options, SplitDetail detail);

// Index helpers for the numbering above.
inline Index faceChildVertex(const Level& parent, Index f) {
  return parent.numVertices + f;
}
inline Index edgeChildVertex(const Level& parent, Index e) {
  return parent.numVertices + parent.numFaces() + e;
}

}  // namespace tessera
