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

#include "core/loop/loop_options.h"
#include "core/topology/level.h"

namespace tessera {

enum class RefineDetail {
  kFull,       // every relation: needed to refine further or evaluate limits
  kFacesOnly,  // faces, sharpness and rules only: enough to interpolate
               // points into this level and draw it (OpenSubdiv's
               // fullTopologyInLastLevel = false)
};

// One parent face's 1-to-4 split in the local indices of the child level
// (docs/ARCHITECTURE.md "Numbering"). The uniform refinement numbers the
// children arithmetically; the sparse hierarchy (core/hierarchy/
// sparse_level.h) numbers only those present; both write the same pattern
// through splitFace and splitEdge, and the same rings through
// writeVertexChildRing and writeEdgeVertexRing (below). The splits are
// inline, splitFace forced so: the
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

// The four child triangles of a face with corners v0..v2 and the vertices
// m0..m2 on its edges 0..2, into out[0 .. 12): corners 0..2, then the middle.
inline void writeChildTriangles(Index* out, Index v0, Index v1, Index v2, Index m0, Index m1, Index m2) {
  out[0] = v0, out[1] = m0, out[2] = m2;
  out[3] = m0, out[4] = v1, out[5] = m1;
  out[6] = m2, out[7] = m1, out[8] = v2;
  out[9] = m1, out[10] = m2, out[11] = m0;
}

// The child faces' vertices alone.
inline void splitFaceVertices(const FaceSplit& split, Level& child) {
  const auto& [v0, v1, v2] = split.corners;
  const auto& [m0, m1, m2] = split.midpoints;
  writeChildTriangles(child.faceVertices.data() + 3 * split.firstFace, v0, v1, v2, m0, m1, m2);
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

  Index* fe = child.faceEdges.data() + 3 * c;
  fe[0] = atStart(0), fe[1] = i0, fe[2] = atEnd(2);
  fe[3] = atEnd(0), fe[4] = atStart(1), fe[5] = i1;
  fe[6] = i2, fe[7] = atEnd(1), fe[8] = atStart(2);
  fe[9] = i2, fe[10] = i0, fe[11] = i1;

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
                      std::array<LocalIndex, 2> local, Level& child) {
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

// The ring of the child of parent vertex v keeps v's ring order: each entry
// becomes the half of its edge at v, the vertex on that edge, and the corner
// child of its face at v, in which v keeps its corner index. firstHalf(e),
// onEdge(e) and firstChild(f) give the child numbering (uniform or sparse).
template <typename FirstHalf, typename OnEdge, typename FirstChild>
inline void writeVertexChildRing(const Level& parent, Index v, FirstHalf firstHalf, OnEdge onEdge,
                                 FirstChild firstChild, Index* ringE, Index* ringV, Index* ringF,
                                 LocalIndex* ringL) {
  const Index from = parent.ringOffsets[v], to = parent.ringOffsets[v + 1];
  for (Index k = from; k < to; ++k) {
    const Index e = parent.ringEdges[k];
    const Index f = parent.ringFaces[k];
    const LocalIndex corner = parent.ringFaceLocal[k];
    ringE[k - from] = firstHalf(e) + (parent.edgeVertices[e][0] == v ? 0 : 1);
    ringV[k - from] = onEdge(e);
    ringF[k - from] = f == kNoIndex ? kNoIndex : firstChild(f) + corner;
    ringL[k - from] = corner;
  }
}

// The ring of the child vertex on a parent edge, in the order OpenSubdiv's
// TriRefinement gives it: from the half towards edgeVertices[1], across the
// three children of the edge's face 0 (which runs the edge from its vertex 0
// to 1, at local j), then those of face 1. Written once for the uniform
// refinement and the sparse hierarchy, each with its own numbering.
struct EdgeVertexRing {
  Index firstHalf = 0;          // the half at edgeVertices[0]; the other is firstHalf + 1
  std::array<Index, 2> ends{};  // the child vertices of edgeVertices[0] and [1]
  struct Side {
    Index firstChild = kNoIndex;      // the face's first child face; kNoIndex: no face (boundary)
    Index firstInterior = 0;          // its first interior child edge
    int local = 0;                    // the edge's position in the face
    std::array<Index, 2> opposite{};  // the child vertices on face edges local+1 and local+2
  };
  std::array<Side, 2> sides;
};

inline void writeEdgeVertexRing(const EdgeVertexRing& r, Index* ringE, Index* ringV, Index* ringF,
                                LocalIndex* ringL) {
  const auto& a = r.sides[0];
  const int j = a.local, jn = (j + 1) % 3, jp = (j + 2) % 3;
  ringE[0] = r.firstHalf + 1, ringV[0] = r.ends[1], ringF[0] = a.firstChild + jn, ringL[0] = j;
  ringE[1] = a.firstInterior + jn, ringV[1] = a.opposite[0], ringF[1] = a.firstChild + 3, ringL[1] = jp;
  ringE[2] = a.firstInterior + j, ringV[2] = a.opposite[1], ringF[2] = a.firstChild + j, ringL[2] = jn;
  ringE[3] = r.firstHalf, ringV[3] = r.ends[0];
  const auto& b = r.sides[1];
  if (b.firstChild == kNoIndex) {
    ringF[3] = kNoIndex, ringL[3] = 0;
    return;
  }
  const int k = b.local, kn = (k + 1) % 3, kp = (k + 2) % 3;
  ringF[3] = b.firstChild + kn, ringL[3] = k;
  ringE[4] = b.firstInterior + kn, ringV[4] = b.opposite[0], ringF[4] = b.firstChild + 3, ringL[4] = kp;
  ringE[5] = b.firstInterior + k, ringV[5] = b.opposite[1], ringF[5] = b.firstChild + k, ringL[5] = kn;
}

Level refineLevel(const Level& parent, const LoopOptions& options, RefineDetail detail = RefineDetail::kFull);

}  // namespace tessera
