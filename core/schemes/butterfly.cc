#include "core/schemes/butterfly.h"

#include <string>

#include "core/loop/refinement.h"
#include "core/loop/surfaces.h"
#include "core/schemes/butterfly_masks.h"

namespace tessera::schemes {

namespace {

// Is v an interior vertex whose valence is not 6?
bool irregularInterior(const Level& level, Index v) {
  return level.valence(v) != 6 && !level.isBoundaryVertex(v);
}

// Zorin's stencil around interior end `a` of the edge towards `b`.
Vec3 irregularStencil(const Level& level, Index a, Index b, std::span<const Vec3> p) {
  auto ring = level.ringVerticesOf(a);
  const int k = static_cast<int>(ring.size());
  int start = 0;
  while (ring[start] != b) ++start;
  Vec3 sum = butterfly::kIrregularVertexWeight * p[a];
  for (int j = 0; j < k; ++j) sum += butterfly::irregularNeighbourWeight(k, j) * p[ring[(start + j) % k]];
  return sum;
}

// The vertex opposite edge e in face f, where e has local index `local`.
Index oppositeIn(const Level& level, Index f, int local) {
  return level.triangleVertices(f)[(local + 2) % 3];
}

// The wing tip across face f's edge `wing` (joining x and b): the opposite
// vertex of the face on the other side, or the reflection x + b - a.
Vec3 wingTip(const Level& level, Index f, Index wing, Index x, Index b, Index a, std::span<const Vec3> p) {
  const auto& ef = level.edgeFaces[wing];
  const int side = ef[0] == f ? 1 : 0;
  if (ef[side] == kNoIndex) return p[x] + p[b] - p[a];
  return p[oppositeIn(level, ef[side], level.edgeFaceLocal[wing][side])];
}

Vec3 edgePoint(const Level& level, Index e, std::span<const Vec3> p) {
  const auto& ev = level.edgeVertices[e];
  const Index a0 = ev[0], a1 = ev[1];
  const auto& ef = level.edgeFaces[e];
  const auto& el = level.edgeFaceLocal[e];
  if (ef[1] == kNoIndex) {
    // 4-point rule along the boundary: the boundary neighbours of each end.
    // Face 0 runs the edge from a0 to a1; the boundary continues past a1 at
    // the first edge of a1's ring and before a0 at the last of a0's ring.
    const Index beyond1 = level.ringVerticesOf(a1)[0];
    auto ring0 = level.ringVerticesOf(a0);
    const Index beyond0 = ring0[ring0.size() - 1];
    return butterfly::kBoundaryEndWeight * (p[a0] + p[a1]) +
           butterfly::kBoundaryOuterWeight * (p[beyond0] + p[beyond1]);
  }
  const bool irregular0 = irregularInterior(level, a0), irregular1 = irregularInterior(level, a1);
  if (!irregular0 && !irregular1) {
    // Face 0 is (a0, a1, b0) from local el[0]; face 1 is (a1, a0, b1).
    const Index f0 = ef[0], f1 = ef[1];
    const Index b0 = oppositeIn(level, f0, el[0]), b1 = oppositeIn(level, f1, el[1]);
    const auto fe0 = level.triangleEdges(f0);
    const auto fe1 = level.triangleEdges(f1);
    Vec3 wings = wingTip(level, f0, fe0[(el[0] + 1) % 3], a1, b0, a0, p) +
                 wingTip(level, f0, fe0[(el[0] + 2) % 3], a0, b0, a1, p) +
                 wingTip(level, f1, fe1[(el[1] + 1) % 3], a0, b1, a1, p) +
                 wingTip(level, f1, fe1[(el[1] + 2) % 3], a1, b1, a0, p);
    return butterfly::kEndWeight * (p[a0] + p[a1]) + butterfly::kOppositeWeight * (p[b0] + p[b1]) +
           butterfly::kWingWeight * wings;
  }
  if (irregular0 && irregular1)
    return 0.5 * (irregularStencil(level, a0, a1, p) + irregularStencil(level, a1, a0, p));
  return irregular0 ? irregularStencil(level, a0, a1, p) : irregularStencil(level, a1, a0, p);
}

}  // namespace

void interpolateButterfly(const Level& parent, std::span<const Vec3> p, std::span<Vec3> c) {
  const Index nV = parent.numVertices;
  for (Index v = 0; v < nV; ++v) c[v] = p[v];
  for (Index e = 0; e < parent.numEdges(); ++e) c[nV + e] = edgePoint(parent, e, p);
}

SurfaceMesh TriangleRefinement::surface() const {
  SurfaceMesh s;
  s.positions = points;
  const Level& finest = levels.back();
  s.triangles = trianglesOf(finest);
  return s;
}

Expected<TriangleRefinement> refineButterfly(const BaseTopology& topology, std::span<const Vec3> points,
                                             int levels, long long maxFaces) {
  if (levels < 0) return invalidArgument("level must be 0 or more, got " + std::to_string(levels));
  BaseTopology plain = topology;  // no tags: the Butterfly has no crease rules
  plain.creases.clear();
  plain.vertexSharpness.clear();
  TESSERA_ASSIGN_OR_RETURN(Level base, buildBaseLevel(plain, LoopOptions{}));
  long long faces = base.numFaces();
  for (int l = 0; l < levels && faces <= maxFaces; ++l) faces *= 4;
  if (faces > maxFaces) {
    return invalidArgument("level " + std::to_string(levels) + " would make more than " +
                           std::to_string(maxFaces) + " triangles; choose a lower level");
  }
  TriangleRefinement out;
  out.levels.push_back(std::move(base));
  out.points.assign(points.begin(), points.end());
  std::vector<Vec3> next;
  for (int l = 0; l < levels; ++l) {
    const Level& parent = out.levels.back();
    next.resize(parent.numVertices + parent.numEdges());
    interpolateButterfly(parent, out.points, next);
    out.points.swap(next);
    out.levels.push_back(refineLevel(parent, LoopOptions{}, RefineDetail::kFull));
  }
  return out;
}

}  // namespace tessera::schemes
