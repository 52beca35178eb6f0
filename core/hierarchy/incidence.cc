#include "core/hierarchy/incidence.h"

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

}  // namespace

FaceId incidentFace(const Level& base, const LevelCounts& counts, VertexId vertex) {
  return {vertex.level(), ofVertex(base, counts, vertex.level(), vertex.index()).face};
}

FaceId incidentFace(const Level& base, const LevelCounts& counts, EdgeId edge) {
  return {edge.level(), ofEdge(base, counts, edge.level(), edge.index()).face};
}

}  // namespace tessera
