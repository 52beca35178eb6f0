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

#include <array>
#include <cstdint>

#include "core/loop/level.h"
#include "core/loop/loop_options.h"

namespace tessera {

enum class RefineDetail {
  kFull,       // every relation: needed to refine further or evaluate limits
  kFacesOnly,  // faces, sharpness and rules only: enough to interpolate
               // points into this level and draw it (OpenSubdiv's
               // fullTopologyInLastLevel = false)
};

// The child of parent edge e that touches its end vertex `end` (2e or 2e+1).
inline Index childEdgeAtEnd(const Level& parent, Index e, Index end) {
  return 2 * e + (parent.edgeVertices[e][0] == end ? 0 : 1);
}

// One parent face's 1-to-4 split in the local indices of the child level
// (docs/ARCHITECTURE.md "Numbering"). The uniform refinement numbers the
// children arithmetically; the sparse hierarchy (core/hierarchy/
// sparse_level.h) numbers only those present; both write the same pattern
// through splitFace and splitEdge. Both are inline, splitFace forced so: the
// uniform refinement runs them for every face and edge of a level, and as a
// call splitFace made that loop run about 15% more instructions (callgrind,
// fandisk refined from level 3 to 4).
struct FaceSplit {
  std::array<Index, 3> corners{};    // the child vertices of face vertices 0..2
  std::array<Index, 3> midpoints{};  // the child vertices on face edges 0..2
  std::array<Index, 3> halves{};     // per face edge: its first half, the one at its edgeVertices[0]
  Index firstInterior = 0;           // the first of the three child edges inside the face
  Index firstFace = 0;               // the first of its four child faces
  uint8_t sides = 0;                 // the parent face's faceEdgeSides
};

// The child faces' vertices alone (RefineDetail::kFacesOnly).
inline void splitFaceVertices(const FaceSplit& split, Level& child) {
  const auto& [v0, v1, v2] = split.corners;
  const auto& [m0, m1, m2] = split.midpoints;
  const Index c = split.firstFace;
  child.faceVertices[c + 0] = {v0, m0, m2};
  child.faceVertices[c + 1] = {m0, v1, m1};
  child.faceVertices[c + 2] = {m2, m1, v2};
  child.faceVertices[c + 3] = {m1, m2, m0};
}

// Child faces firstFace .. firstFace + 3 (corners 0..2, then the middle):
// their vertices, edges and edge sides; and the three interior edges: their
// vertices, faces and positions in them.
[[gnu::always_inline]] inline void splitFace(const FaceSplit& split, Level& child) {
  splitFaceVertices(split, child);
  const auto& [m0, m1, m2] = split.midpoints;
  const uint8_t sides = split.sides;
  const Index i0 = split.firstInterior, i1 = i0 + 1, i2 = i0 + 2;
  const Index c = split.firstFace;
  // Halves of face edge j at its start (vertex j) and end (vertex j+1).
  auto atStart = [&](int j) { return split.halves[j] + ((sides >> j) & 1); };
  auto atEnd = [&](int j) { return split.halves[j] + 1 - ((sides >> j) & 1); };

  child.faceEdges[c + 0] = {atStart(0), i0, atEnd(2)};
  child.faceEdges[c + 1] = {atEnd(0), atStart(1), i1};
  child.faceEdges[c + 2] = {i2, atEnd(1), atStart(2)};
  child.faceEdges[c + 3] = {i2, i0, i1};

  // Corner children are face 0 of the interior edges, the middle is face 1.
  child.faceEdgeSides[c + 0] = sides & 0b101;
  child.faceEdgeSides[c + 1] = sides & 0b011;
  child.faceEdgeSides[c + 2] = sides & 0b110;
  child.faceEdgeSides[c + 3] = 0b111;

  // Interior edge j joins the midpoints of face edges j and j-1.
  child.edgeVertices[i0] = {m0, m2};
  child.edgeVertices[i1] = {m1, m0};
  child.edgeVertices[i2] = {m2, m1};
  child.edgeFaces[i0] = {c + 0, c + 3};
  child.edgeFaces[i1] = {c + 1, c + 3};
  child.edgeFaces[i2] = {c + 2, c + 3};
  child.edgeFaceLocal[i0] = {1, 1};
  child.edgeFaceLocal[i1] = {2, 2};
  child.edgeFaceLocal[i2] = {0, 0};
}

// The two halves of a parent edge: firstHalf runs from `from` (the child of
// its edgeVertices[0]) to the vertex `middle` on it, firstHalf + 1 from
// `middle` to `to`. `children` holds the first child of each of the edge's
// faces (a negative value, no face or no child there, is kept as it is) and
// `local` the edge's position in each, which each half keeps in the corner
// child at its end.
inline void splitEdge(Index firstHalf, Index from, Index middle, Index to, std::array<Index, 2> children,
                      std::array<uint8_t, 2> local, Level& child) {
  child.edgeVertices[firstHalf] = {from, middle};
  child.edgeVertices[firstHalf + 1] = {middle, to};
  // A half keeps its parent's slot in the corner child at its end: the
  // corner at end 0 is local j in face 0 and local k+1 in face 1.
  const Index a = children[0], b = children[1];
  const int j = local[0], k = local[1];
  child.edgeFaces[firstHalf] = {a < 0 ? a : a + j, b < 0 ? b : b + (k + 1) % 3};
  child.edgeFaces[firstHalf + 1] = {a < 0 ? a : a + (j + 1) % 3, b < 0 ? b : b + k};
  child.edgeFaceLocal[firstHalf] = local;
  child.edgeFaceLocal[firstHalf + 1] = local;
}

Level refineLevel(const Level& parent, const LoopOptions& options, RefineDetail detail = RefineDetail::kFull);

}  // namespace tessera
