#include "core/hierarchy/incidence.h"

#include <string>

#include "core/hierarchy/quad_incidence.h"

namespace tessera {

namespace {

// A face holding the element, the element's local position in it and, for
// an edge, whether the face runs it from its vertex 1 to 0 (faceEdgeSides).
struct Incidence {
  uint64_t face;
  int local;
  int side;
};

// The children follow refinement.cc: corner child j keeps face vertex j at
// corner j; the middle child 3 reads (m1, m2, m0); the half of edge j at its
// start lies in corner child j at local j, the half at its end in corner
// child j+1 at local j, both oriented as the parent; interior edge j lies in
// corner child j at local j+1, which runs it forwards.
Incidence ofEdge(const Level& base, const LevelCounts& counts, int level, uint64_t index);

Incidence ofVertex(const Level& base, const LevelCounts& counts, int level, uint64_t index) {
  if (level == 0) {
    const Index k = base.ringOffsets[static_cast<Index>(index)];
    return {static_cast<uint64_t>(base.ringFaces[k]), base.ringFaceLocal[k], 0};
  }
  if (index < counts.vertices(level - 1)) {
    const Incidence p = ofVertex(base, counts, level - 1, index);
    return {4 * p.face + p.local, p.local, 0};
  }
  const Incidence p = ofEdge(base, counts, level - 1, index - counts.vertices(level - 1));
  return {4 * p.face + 3, (p.local + 2) % 3, 0};
}

Incidence ofEdge(const Level& base, const LevelCounts& counts, int level, uint64_t index) {
  if (level == 0) {
    const Index e = static_cast<Index>(index);
    return {static_cast<uint64_t>(base.edgeFaces[e][0]), base.edgeFaceLocal[e][0], 0};
  }
  const uint64_t halves = 2 * counts.edges(level - 1);
  if (index < halves) {
    const Incidence p = ofEdge(base, counts, level - 1, index / 2);
    const int end = static_cast<int>(index % 2);
    // The half at the edge's end 0 touches face vertex `local` when the face
    // runs the edge forwards (side 0), vertex local+1 otherwise.
    const bool atStart = end == p.side;
    return {4 * p.face + static_cast<uint64_t>(atStart ? p.local : (p.local + 1) % 3), p.local, p.side};
  }
  const uint64_t rest = index - halves;
  const int j = static_cast<int>(rest % 3);
  return {4 * (rest / 3) + static_cast<uint64_t>(j), (j + 1) % 3, 0};
}

// What follows reads the numbering of refinement.cc with ids in place of
// local indices, one level at a time down from the base.
constexpr uint64_t kNoFace = ~uint64_t{0};

// A face's edges (face edge j joins face vertices j and j+1) and its
// faceEdgeSides bits.
struct FaceEdges {
  std::array<uint64_t, 3> edges;
  uint8_t sides;
};

FaceEdges faceEdgesOf(const Level& base, const LevelCounts& counts, int level, uint64_t face) {
  if (level == 0) {
    const auto fe = base.triangleEdges(static_cast<Index>(face));
    return {{static_cast<uint64_t>(fe[0]), static_cast<uint64_t>(fe[1]), static_cast<uint64_t>(fe[2])},
            base.faceEdgeSides[static_cast<Index>(face)]};
  }
  const FaceEdges p = faceEdgesOf(base, counts, level - 1, face / 4);
  const uint64_t i0 = 2 * counts.edges(level - 1) + 3 * (face / 4);
  // The halves of parent face edge j at its start (vertex j) and its end.
  auto atStart = [&](int j) { return 2 * p.edges[j] + ((p.sides >> j) & 1u); };
  auto atEnd = [&](int j) { return 2 * p.edges[j] + 1 - ((p.sides >> j) & 1u); };
  switch (face % 4) {
    case 0:
      return {{atStart(0), i0, atEnd(2)}, static_cast<uint8_t>(p.sides & 0b101)};
    case 1:
      return {{atEnd(0), atStart(1), i0 + 1}, static_cast<uint8_t>(p.sides & 0b011)};
    case 2:
      return {{i0 + 2, atEnd(1), atStart(2)}, static_cast<uint8_t>(p.sides & 0b110)};
    default:
      return {{i0 + 2, i0, i0 + 1}, 0b111};
  }
}

// The faces on either side of an edge (kNoFace beyond a boundary) and the
// edge's position in each.
struct EdgeFaces {
  std::array<uint64_t, 2> faces;
  std::array<int, 2> locals;
};

EdgeFaces edgeFacesOf(const Level& base, const LevelCounts& counts, int level, uint64_t index) {
  if (level == 0) {
    const auto& ef = base.edgeFaces[static_cast<Index>(index)];
    const auto& el = base.edgeFaceLocal[static_cast<Index>(index)];
    return {{static_cast<uint64_t>(ef[0]), ef[1] == kNoIndex ? kNoFace : static_cast<uint64_t>(ef[1])},
            {el[0], el[1]}};
  }
  const uint64_t halves = 2 * counts.edges(level - 1);
  if (index < halves) {
    // A half keeps its parent's position, in the corner child at its end.
    const EdgeFaces p = edgeFacesOf(base, counts, level - 1, index / 2);
    const int end = static_cast<int>(index % 2);
    const uint64_t second = p.faces[1] == kNoFace ? kNoFace : 4 * p.faces[1] + (p.locals[1] + 1 - end) % 3;
    return {{4 * p.faces[0] + static_cast<uint64_t>((p.locals[0] + end) % 3), second}, p.locals};
  }
  // Interior edge j of face f: corner child j, then the middle child.
  const uint64_t f = (index - halves) / 3;
  const int j = static_cast<int>((index - halves) % 3);
  return {{4 * f + static_cast<uint64_t>(j), 4 * f + 3}, {(j + 1) % 3, (j + 1) % 3}};
}

std::array<uint64_t, 2> endsOf(const Level& base, const LevelCounts& counts, int level, uint64_t index) {
  if (level == 0) {
    const auto& ev = base.edgeVertices[static_cast<Index>(index)];
    return {static_cast<uint64_t>(ev[0]), static_cast<uint64_t>(ev[1])};
  }
  const uint64_t nV = counts.vertices(level - 1);
  const uint64_t halves = 2 * counts.edges(level - 1);
  if (index < halves) {
    // Half 2e runs (end 0, middle), half 2e+1 runs (middle, end 1).
    const auto p = endsOf(base, counts, level - 1, index / 2);
    const uint64_t middle = nV + index / 2;
    return index % 2 == 0 ? std::array<uint64_t, 2>{p[0], middle} : std::array<uint64_t, 2>{middle, p[1]};
  }
  // Interior edge j joins the vertices on face edges j and j-1.
  const auto fe = faceEdgesOf(base, counts, level - 1, (index - halves) / 3).edges;
  const int j = static_cast<int>((index - halves) % 3);
  return {nV + fe[j], nV + fe[(j + 2) % 3]};
}

}  // namespace

FaceId incidentFace(const Level& base, const LevelCounts& counts, VertexId vertex) {
  if (counts.quads()) return quad_incidence::incidentFace(base, counts, vertex);
  return {vertex.level(), ofVertex(base, counts, vertex.level(), vertex.index()).face};
}

FaceId incidentFace(const Level& base, const LevelCounts& counts, EdgeId edge) {
  if (counts.quads()) return quad_incidence::incidentFace(base, counts, edge);
  return {edge.level(), ofEdge(base, counts, edge.level(), edge.index()).face};
}

std::array<VertexId, 2> edgeEnds(const Level& base, const LevelCounts& counts, EdgeId edge) {
  if (counts.quads()) return quad_incidence::edgeEnds(base, counts, edge);
  const auto ends = endsOf(base, counts, edge.level(), edge.index());
  return {VertexId(edge.level(), ends[0]), VertexId(edge.level(), ends[1])};
}

Expected<EdgeId> edgeBetween(const Level& base, const LevelCounts& counts, VertexId a, VertexId b) {
  TESSERA_RETURN_IF_ERROR(counts.check(a));
  TESSERA_RETURN_IF_ERROR(counts.check(b));
  const std::string both = a.toString() + " and " + b.toString();
  if (a.level() != b.level())
    return invalidArgument(both + " lie on different levels: an edge joins vertices of one level");
  if (a == b) return invalidArgument(both + " are the same vertex: an edge needs two");
  const int level = a.level();
  const Status apart = invalidArgument(both + " are not joined by an edge of level " + std::to_string(level));
  if (level == 0) {
    const Index v = static_cast<Index>(a.index());
    for (Index k = base.ringOffsets[v]; k < base.ringOffsets[v + 1]; ++k) {
      if (static_cast<uint64_t>(base.ringVertices[k]) == b.index())
        return EdgeId(0, static_cast<uint64_t>(base.ringEdges[k]));
    }
    return apart;
  }
  if (counts.quads()) return quad_incidence::edgeBetween(base, counts, a, b, apart);
  // Vertices of the parent level are joined only to vertices on parent edges.
  const uint64_t nV = counts.vertices(level - 1);
  const bool aOld = a.index() < nV, bOld = b.index() < nV;
  if (aOld && bOld) return apart;
  if (aOld || bOld) {
    const uint64_t old = aOld ? a.index() : b.index();
    const uint64_t e = (aOld ? b.index() : a.index()) - nV;
    const auto ends = endsOf(base, counts, level - 1, e);
    for (uint64_t end = 0; end < 2; ++end) {
      if (ends[end] == old) return EdgeId(level, 2 * e + end);
    }
    return apart;
  }
  // Two vertices on parent edges: joined inside a parent face holding both.
  const uint64_t e1 = a.index() - nV, e2 = b.index() - nV;
  for (uint64_t f : edgeFacesOf(base, counts, level - 1, e1).faces) {
    if (f == kNoFace) continue;
    const auto fe = faceEdgesOf(base, counts, level - 1, f).edges;
    for (int j = 0; j < 3; ++j) {
      const uint64_t p = fe[j], q = fe[(j + 2) % 3];
      if ((p == e1 && q == e2) || (p == e2 && q == e1)) {
        return EdgeId(level, 2 * counts.edges(level - 1) + 3 * f + static_cast<uint64_t>(j));
      }
    }
  }
  return apart;
}

}  // namespace tessera
