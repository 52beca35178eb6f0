// One element at a time, the quad split of core/catmark/quad_split.h
// (Catmull-Clark and bilinear topology): the
// child faces of a parent face, its interior child edges, the halves of a
// parent edge, and the rings of the three kinds of child vertex. The uniform
// split numbers the children arithmetically; the sparse hierarchy
// (core/hierarchy/sparse_level.h) numbers only those present; both write
// the same pattern through these functions, as the Loop split does through
// core/loop/refinement.h.
//
// `Links` gives the child numbering:
//   vertexChild(v)  the child of parent vertex v;
//   faceVertex(f)   the vertex in parent face f;
//   edgeVertex(e)   the vertex on parent edge e;
//   halves(e)       the first of e's two halves: halves(e) + end joins
//                   edgeVertex(e) to the child of edgeVertices[e][end];
//   firstFace(f)    the first of f's faceSize(f) children, child j at
//                   corner j (negative: f has no children);
//   interior(f)     the first of f's faceSize(f) interior edges, edge j
//                   joining faceVertex(f) to edgeVertex(faceEdges[j]).
// Conventions are OpenSubdiv's QuadRefinement: a quad's child j keeps its
// corner vertex at position j, an n-gon's child j has it at position 0.
#pragma once

#include "core/topology/level.h"

namespace tessera::topology {

// Where child j of a face of `size` corners holds its slot k (0: the
// corner, 1: the vertex on the edge leaving it, 2: the face vertex, 3: the
// vertex on the edge arriving).
inline int quadChildSlot(int size, int j, int k) {
  return size == 4 ? (j + k) & 3 : k;
}

// The children of parent face f: their vertices, and with `withEdges`
// their edges.
template <typename Links>
inline void splitQuadFace(const Level& parent, Index f, const Links& links, bool withEdges, Level& child) {
  const Index o = parent.faceBegin(f);
  const int n = parent.faceSize(f);
  const Index* fv = parent.faceVertices.data() + o;
  const Index* fe = parent.faceEdges.data() + o;
  const Index first = links.firstFace(f), interior = links.interior(f), center = links.faceVertex(f);
  for (int j = 0; j < n; ++j) {
    const int jPrev = j ? j - 1 : n - 1;
    Index* cv = child.faceVertices.data() + 4 * (first + j);
    cv[quadChildSlot(n, j, 0)] = links.vertexChild(fv[j]);
    cv[quadChildSlot(n, j, 1)] = links.edgeVertex(fe[j]);
    cv[quadChildSlot(n, j, 2)] = center;
    cv[quadChildSlot(n, j, 3)] = links.edgeVertex(fe[jPrev]);
    if (!withEdges) continue;
    Index* ce = child.faceEdges.data() + 4 * (first + j);
    const int nextEnd = parent.edgeVertices[fe[j]][0] == fv[j] ? 0 : 1;
    const int prevEnd = parent.edgeVertices[fe[jPrev]][0] == fv[j] ? 0 : 1;
    ce[quadChildSlot(n, j, 0)] = links.halves(fe[j]) + nextEnd;
    ce[quadChildSlot(n, j, 1)] = interior + j;
    ce[quadChildSlot(n, j, 2)] = interior + jPrev;
    ce[quadChildSlot(n, j, 3)] = links.halves(fe[jPrev]) + prevEnd;
  }
}

// The interior edges of parent face f: edge j lies between children j and j+1.
template <typename Links>
inline void splitQuadFaceEdges(const Level& parent, Index f, const Links& links, Level& child) {
  const Index o = parent.faceBegin(f);
  const int n = parent.faceSize(f);
  const Index first = links.firstFace(f), interior = links.interior(f), center = links.faceVertex(f);
  for (int j = 0; j < n; ++j) {
    const int jNext = j + 1 < n ? j + 1 : 0;
    child.edgeVertices[interior + j] = {center, links.edgeVertex(parent.faceEdges[o + j])};
    child.edgeFaces[interior + j] = {first + j, first + jNext};
    child.edgeFaceLocal[interior + j] = {static_cast<LocalIndex>(n == 4 ? jNext : 1),
                                         static_cast<LocalIndex>(n == 4 ? (jNext + 2) & 3 : 2)};
  }
}

// The halves of parent edge e: each lies in the child, of each of e's
// faces, at its end. A face without children (a sparse level's) leaves
// `absent` in its place, and no face leaves kNoIndex.
template <typename Links>
inline void splitQuadEdge(const Level& parent, Index e, const Links& links, Index absent, Level& child) {
  const auto& ev = parent.edgeVertices[e];
  const auto& ef = parent.edgeFaces[e];
  const auto& el = parent.edgeFaceLocal[e];
  for (int end = 0; end < 2; ++end) {
    const Index c = links.halves(e) + end;
    child.edgeVertices[c] = {links.edgeVertex(e), links.vertexChild(ev[end])};
    child.edgeFaces[c] = {kNoIndex, kNoIndex};
    child.edgeFaceLocal[c] = {0, 0};
    for (int i = 0; i < 2 && ef[i] != kNoIndex; ++i) {
      const Index first = ef[i] < 0 ? absent : links.firstFace(ef[i]);
      if (first < 0) {
        child.edgeFaces[c][i] = absent;
        continue;
      }
      const Index o = parent.faceBegin(ef[i]);
      const int n = parent.faceSize(ef[i]);
      const int edgeInFace = el[i];
      const int childOfEdge = parent.faceVertices[o + edgeInFace] != ev[end] ? 1 : 0;
      int childInFace = edgeInFace + childOfEdge;
      if (childInFace == n) childInFace = 0;
      child.edgeFaces[c][i] = first + childInFace;
      child.edgeFaceLocal[c][i] = static_cast<LocalIndex>(n == 4 ? edgeInFace : (childOfEdge ? 3 : 0));
    }
  }
}

// The size of each child vertex's ring.
inline int quadEdgeVertexValence(const Level& parent, Index e) {
  return parent.isBoundaryEdge(e) ? 3 : 4;
}

// The child of parent vertex v keeps v's ring order: the halves at v and
// v's corner children.
template <typename Links>
inline void writeQuadVertexChildRing(const Level& parent, Index v, const Links& links, Index* ringE,
                                     Index* ringV, Index* ringF, LocalIndex* ringL) {
  const Index from = parent.ringOffsets[v], to = parent.ringOffsets[v + 1];
  for (Index k = from; k < to; ++k) {
    const Index e = parent.ringEdges[k];
    ringE[k - from] = links.halves(e) + (parent.edgeVertices[e][0] == v ? 0 : 1);
    ringV[k - from] = links.edgeVertex(e);
    const Index f = parent.ringFaces[k];
    if (f == kNoIndex) {
      ringF[k - from] = kNoIndex, ringL[k - from] = 0;
    } else {
      const int c = parent.ringFaceLocal[k];
      ringF[k - from] = links.firstFace(f) + c;
      ringL[k - from] = static_cast<LocalIndex>(parent.faceSize(f) == 4 ? c : 0);
    }
  }
}

// The vertex in parent face f: child k lies between the edges to edge
// k-1's and edge k's vertices.
template <typename Links>
inline void writeQuadFaceVertexRing(const Level& parent, Index f, const Links& links, Index* ringE,
                                    Index* ringV, Index* ringF, LocalIndex* ringL) {
  const Index o = parent.faceBegin(f);
  const int n = parent.faceSize(f);
  const Index first = links.firstFace(f), interior = links.interior(f);
  for (int k = 0; k < n; ++k) {
    const int kPrev = k ? k - 1 : n - 1;
    ringE[k] = interior + kPrev;
    ringV[k] = links.edgeVertex(parent.faceEdges[o + kPrev]);
    ringF[k] = first + k;
    ringL[k] = static_cast<LocalIndex>(n == 4 ? (k + 2) & 3 : 2);
  }
}

// The vertex on parent edge e: face 0 runs the edge from a to b; the ring
// starts with the half towards b, crosses face 0's two children, then
// face 1's.
template <typename Links>
inline void writeQuadEdgeVertexRing(const Level& parent, Index e, const Links& links, Index* ringE,
                                    Index* ringV, Index* ringF, LocalIndex* ringL) {
  const auto& ev = parent.edgeVertices[e];
  const auto& ef = parent.edgeFaces[e];
  const auto& el = parent.edgeFaceLocal[e];
  const Index o0 = parent.faceBegin(ef[0]);
  const int n0 = parent.faceSize(ef[0]);
  const int j0 = el[0];
  const int j0Next = j0 + 1 < n0 ? j0 + 1 : 0;
  const int b = parent.faceVertices[o0 + j0] == ev[0] ? 1 : 0;  // end of the edge face 0 runs to
  const Index h = links.halves(e);
  ringE[0] = h + b;
  ringV[0] = links.vertexChild(ev[b]);
  ringF[0] = links.firstFace(ef[0]) + j0Next;
  ringL[0] = static_cast<LocalIndex>(n0 == 4 ? j0 : 3);
  ringE[1] = links.interior(ef[0]) + j0;
  ringV[1] = links.faceVertex(ef[0]);
  ringF[1] = links.firstFace(ef[0]) + j0;
  ringL[1] = static_cast<LocalIndex>(n0 == 4 ? j0Next : 1);
  ringE[2] = h + (1 - b);
  ringV[2] = links.vertexChild(ev[1 - b]);
  if (ef[1] == kNoIndex) {
    ringF[2] = kNoIndex, ringL[2] = 0;
    return;
  }
  const int n1 = parent.faceSize(ef[1]);
  const int j1 = el[1];
  const int j1Next = j1 + 1 < n1 ? j1 + 1 : 0;
  ringF[2] = links.firstFace(ef[1]) + j1Next;
  ringL[2] = static_cast<LocalIndex>(n1 == 4 ? j1 : 3);
  ringE[3] = links.interior(ef[1]) + j1;
  ringV[3] = links.faceVertex(ef[1]);
  ringF[3] = links.firstFace(ef[1]) + j1;
  ringL[3] = static_cast<LocalIndex>(n1 == 4 ? j1Next : 1);
}

}  // namespace tessera::topology
