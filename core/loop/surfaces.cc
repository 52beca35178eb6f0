#include "core/loop/surfaces.h"

#include "core/loop/limit.h"
#include "core/mesh/vertex_normals.h"

namespace tessera {

std::vector<std::array<int, 3>> trianglesOf(const Level& level) {
  std::vector<std::array<int, 3>> triangles(level.numFaces());
  for (Index f = 0; f < level.numFaces(); ++f) {
    const auto fv = level.triangleVertices(f);
    triangles[f] = {fv[0], fv[1], fv[2]};
  }
  return triangles;
}

SurfaceMesh controlSurfaceOf(const Level& level, std::span<const Vec3> points) {
  SurfaceMesh surface;
  surface.positions.assign(points.begin(), points.begin() + level.numVertices);
  surface.triangles = trianglesOf(level);
  surface.normals = areaWeightedVertexNormals(surface.positions, surface.triangles);
  return surface;
}

Expected<SurfaceMesh> limitSurfaceOf(const Level& level, std::span<const Vec3> points, CreaseMethod method) {
  if (!level.fullTopology) return invalidArgument("limit evaluation needs the level's full topology");
  SurfaceMesh surface;
  surface.positions.resize(level.numVertices);
  surface.normals.resize(level.numVertices);
  surface.triangles = trianglesOf(level);
  computeLimit(level, points, surface.positions, surface.normals, method);
  // Each further side of a crease or corner gets a copy of the vertex with
  // its own limit normal; the faces of that side are pointed at the copy.
  for (Index v = 0; v < level.numVertices; ++v) {
    if (isSmoothLike(level.vertexRules[v])) continue;
    auto ringF = level.ringFacesOf(v);
    const int n = level.valence(v);
    for (const LimitSector& sector : otherLimitSectors(level, v, points, method)) {
      const int copy = static_cast<int>(surface.positions.size());
      surface.positions.push_back(surface.positions[v]);
      surface.normals.push_back(sector.normal);
      for (int k = sector.firstFace; k < sector.firstFace + sector.faceCount; ++k) {
        const int ring = k % n;
        surface.triangles[ringF[ring]][level.ringFaceLocal[level.ringOffsets[v] + ring]] = copy;
      }
    }
  }
  return surface;
}

}  // namespace tessera
