#include "core/hierarchy/quad_incidence.h"

#include "core/topology/quad_split_parts.h"

namespace tessera::quad_incidence {

namespace {

using topology::quadChildSlot;

// A face holding an element, the element's position in it and, for an
// edge, whether the face runs it from its second end to its first.
struct Incidence {
  uint64_t face;
  int local;
  int side;
};

// Face f of `level`: where its children start, and its size.
struct Parent {
  uint64_t face;
  uint64_t firstChild;
  int size;
};
Parent parentOf(const LevelCounts& counts, int level, uint64_t child) {
  const FaceId p = counts.parentFace(FaceId(level, child));
  return {p.index(), counts.firstChildFace(p), counts.faceSize(p)};
}

// Edge k of face f of `level` and whether f runs it backwards.
struct FaceEdge {
  uint64_t edge;
  int side;
};

FaceEdge faceEdgeAt(const Level& base, const LevelCounts& counts, int level, uint64_t face, int k) {
  if (level == 0) {
    const Index at = base.faceBegin(static_cast<Index>(face)) + k;
    const Index e = base.faceEdges[at];
    return {static_cast<uint64_t>(e), base.edgeVertices[e][0] != base.faceVertices[at] ? 1 : 0};
  }
  // The child's slot kind at position k (quad_split_parts.h): 0 the half of
  // the parent's edge j at the corner, 1 interior edge j, 2 interior edge
  // j-1, 3 the half of the parent's edge j-1 at the corner.
  const Parent p = parentOf(counts, level, face);
  const int j = static_cast<int>(face - p.firstChild), n = p.size;
  const int kind = n == 4 ? (k - j + 4) & 3 : k;
  const int jPrev = j ? j - 1 : n - 1;
  const uint64_t corners = counts.corners(level - 1);
  switch (kind) {
    case 0: {
      const FaceEdge pe = faceEdgeAt(base, counts, level - 1, p.face, j);
      return {corners + 2 * pe.edge + static_cast<uint64_t>(pe.side), 1};
    }
    case 1:
      return {p.firstChild + static_cast<uint64_t>(j), 1};
    case 2:
      return {p.firstChild + static_cast<uint64_t>(jPrev), 0};
    default: {
      const FaceEdge pe = faceEdgeAt(base, counts, level - 1, p.face, jPrev);
      return {corners + 2 * pe.edge + static_cast<uint64_t>(1 - pe.side), 0};
    }
  }
}

Incidence ofEdge(const Level& base, const LevelCounts& counts, int level, uint64_t index) {
  if (level == 0) {
    const Index e = static_cast<Index>(index);
    return {static_cast<uint64_t>(base.edgeFaces[e][0]), base.edgeFaceLocal[e][0], 0};
  }
  const uint64_t corners = counts.corners(level - 1);
  if (index < corners) {  // interior edge j of its parent face, in child j, run backwards
    const Parent p = parentOf(counts, level, index);
    const int j = static_cast<int>(index - p.firstChild);
    return {index, quadChildSlot(p.size, j, 1), 1};
  }
  const uint64_t e = (index - corners) / 2;
  const int end = static_cast<int>((index - corners) % 2);
  const Incidence p = ofEdge(base, counts, level - 1, e);
  const FaceId pf(level - 1, p.face);
  const int n = counts.faceSize(pf);
  const uint64_t first = counts.firstChildFace(pf);
  // The face runs the parent edge from its corner `local`, which is the
  // edge's end `side`: the half at that end lies in that corner's child.
  if (end == p.side) return {first + static_cast<uint64_t>(p.local), quadChildSlot(n, p.local, 0), 1};
  const int next = p.local + 1 < n ? p.local + 1 : 0;
  return {first + static_cast<uint64_t>(next), quadChildSlot(n, next, 3), 0};
}

Incidence ofVertex(const Level& base, const LevelCounts& counts, int level, uint64_t index) {
  if (level == 0) {
    const Index k = base.ringOffsets[static_cast<Index>(index)];
    return {static_cast<uint64_t>(base.ringFaces[k]), base.ringFaceLocal[k], 0};
  }
  const uint64_t vertices = counts.vertices(level - 1), faces = counts.faces(level - 1);
  Incidence p{};
  int kind = 0;
  if (index < vertices) {
    p = ofVertex(base, counts, level - 1, index);  // the corner's child
  } else if (index < vertices + faces) {
    p = {index - vertices, 0, 0}, kind = 2;  // the face vertex, in child 0
  } else {
    p = ofEdge(base, counts, level - 1, index - vertices - faces), kind = 1;  // in the child at its start
  }
  const FaceId pf(level - 1, p.face);
  return {counts.firstChildFace(pf) + static_cast<uint64_t>(p.local),
          quadChildSlot(counts.faceSize(pf), p.local, kind), 0};
}

std::array<uint64_t, 2> endsOf(const Level& base, const LevelCounts& counts, int level, uint64_t index) {
  if (level == 0) {
    const auto& ev = base.edgeVertices[static_cast<Index>(index)];
    return {static_cast<uint64_t>(ev[0]), static_cast<uint64_t>(ev[1])};
  }
  const uint64_t vertices = counts.vertices(level - 1), faces = counts.faces(level - 1);
  const uint64_t corners = counts.corners(level - 1);
  if (index < corners) {  // interior edge j: the face vertex, then the vertex on the face's edge j
    const Parent p = parentOf(counts, level, index);
    const FaceEdge pe = faceEdgeAt(base, counts, level - 1, p.face, static_cast<int>(index - p.firstChild));
    return {vertices + p.face, vertices + faces + pe.edge};
  }
  // Half C + 2e + end: the vertex on e, then the child of e's end `end`.
  const uint64_t e = (index - corners) / 2;
  const auto parentEnds = endsOf(base, counts, level - 1, e);
  return {vertices + faces + e, parentEnds[(index - corners) % 2]};
}

}  // namespace

FaceId incidentFace(const Level& base, const LevelCounts& counts, VertexId vertex) {
  return {vertex.level(), ofVertex(base, counts, vertex.level(), vertex.index()).face};
}

FaceId incidentFace(const Level& base, const LevelCounts& counts, EdgeId edge) {
  return {edge.level(), ofEdge(base, counts, edge.level(), edge.index()).face};
}

std::array<VertexId, 2> edgeEnds(const Level& base, const LevelCounts& counts, EdgeId edge) {
  const auto ends = endsOf(base, counts, edge.level(), edge.index());
  return {VertexId(edge.level(), ends[0]), VertexId(edge.level(), ends[1])};
}

Expected<EdgeId> edgeBetween(const Level& base, const LevelCounts& counts, VertexId a, VertexId b,
                             const Status& apart) {
  // A child of a parent vertex is joined only to vertices on parent edges
  // (by a half), a face vertex only to vertices on its face's edges (by an
  // interior edge).
  const int level = a.level();
  using Origin = LevelCounts::Origin;
  const Origin oa = counts.originOf(a), ob = counts.originOf(b);
  if ((oa == Origin::kEdge) == (ob == Origin::kEdge)) return apart;
  const VertexId onEdge = oa == Origin::kEdge ? a : b, other = oa == Origin::kEdge ? b : a;
  const EdgeId e = counts.parentEdge(onEdge);
  const uint64_t corners = counts.corners(level - 1);
  if (counts.originOf(other) == Origin::kVertex) {
    const auto ends = endsOf(base, counts, level - 1, e.index());
    for (uint64_t end = 0; end < 2; ++end) {
      if (ends[end] == other.index()) return EdgeId(level, corners + 2 * e.index() + end);
    }
    return apart;
  }
  const FaceId f = counts.parentFaceOfVertex(other);
  for (int j = 0; j < counts.faceSize(f); ++j) {
    if (faceEdgeAt(base, counts, level - 1, f.index(), j).edge == e.index())
      return EdgeId(level, counts.firstChildFace(f) + static_cast<uint64_t>(j));
  }
  return apart;
}

}  // namespace tessera::quad_incidence
