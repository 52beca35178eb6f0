#include "core/schemes/sqrt3.h"

#include <string>

#include "core/schemes/sqrt3_masks.h"

namespace tessera::schemes {

void interpolateSqrt3(const Level& parent, std::span<const Vec3> p, std::span<Vec3> c) {
  const Index nV = parent.numVertices;
  for (Index v = 0; v < nV; ++v) {
    auto ring = parent.ringVerticesOf(v);
    const int n = static_cast<int>(ring.size());
    Vec3 sum(0, 0, 0);
    for (Index u : ring) sum += p[u];
    const double a = sqrt3::alpha(n);
    c[v] = (1.0 - a) * p[v] + (a / n) * sum;
  }
  for (Index f = 0; f < parent.numFaces(); ++f) {
    const auto fv = parent.triangleVertices(f);
    c[nV + f] = sqrt3::kFacePointWeight * (p[fv[0]] + p[fv[1]] + p[fv[2]]);
  }
}

std::vector<std::array<int, 3>> sqrt3ChildTriangles(const Level& parent) {
  const Index nV = parent.numVertices;
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(2 * parent.numEdges());
  for (Index e = 0; e < parent.numEdges(); ++e) {
    const auto& ev = parent.edgeVertices[e];
    const auto& ef = parent.edgeFaces[e];
    // edgeFaces[0] runs the edge from edgeVertices[0] to [1].
    const Index cf = nV + ef[0], cg = nV + ef[1];
    triangles.push_back({ev[0], cg, cf});
    triangles.push_back({cg, ev[1], cf});
  }
  return triangles;
}

std::vector<Vec3> sqrt3LimitPositions(const Level& level, std::span<const Vec3> p) {
  std::vector<Vec3> out(level.numVertices);
  for (Index v = 0; v < level.numVertices; ++v) {
    auto ring = level.ringVerticesOf(v);
    const int n = static_cast<int>(ring.size());
    Vec3 sum(0, 0, 0);
    for (Index u : ring) sum += p[u];
    const double w = sqrt3::limitNeighbourWeight(n);
    out[v] = (1.0 - n * w) * p[v] + w * sum;
  }
  return out;
}

Expected<TriangleRefinement> refineSqrt3(const BaseTopology& topology, std::span<const Vec3> points,
                                         int levels, long long maxFaces) {
  if (levels < 0) return invalidArgument("level must be 0 or more, got " + std::to_string(levels));
  BaseTopology plain = topology;
  plain.creases.clear();
  plain.vertexSharpness.clear();
  TESSERA_ASSIGN_OR_RETURN(Level base, buildBaseLevel(plain, LoopOptions{}));
  for (Index e = 0; e < base.numEdges(); ++e) {
    if (base.isBoundaryEdge(e)) {
      return unsupported("sqrt3 refines closed meshes only: edge " + std::to_string(base.edgeVertices[e][0]) +
                         "-" + std::to_string(base.edgeVertices[e][1]) + " is on a boundary");
    }
  }
  long long faces = base.numFaces();
  for (int l = 0; l < levels && faces <= maxFaces; ++l) faces *= 3;
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
    next.resize(parent.numVertices + parent.numFaces());
    interpolateSqrt3(parent, out.points, next);
    out.points.swap(next);
    BaseTopology child;
    child.numVertices = static_cast<int>(out.points.size());
    child.triangles = sqrt3ChildTriangles(parent);
    TESSERA_ASSIGN_OR_RETURN(Level level, buildBaseLevel(child, LoopOptions{}));
    out.levels.push_back(std::move(level));
  }
  return out;
}

}  // namespace tessera::schemes
