#include "core/catmark/surfaces.h"

#include "core/catmark/limit.h"
#include "core/mesh/vertex_normals.h"

namespace tessera {

namespace {

void addPolygons(const Level& level, SurfaceMesh& surface) {
  surface.triangles.reserve(level.faceVertices.size() - 2 * static_cast<size_t>(level.numFaces()));
  surface.polygonOffsets.reserve(static_cast<size_t>(level.numFaces()) + 1);
  surface.polygonCorners.reserve(level.faceVertices.size());
  for (Index f = 0; f < level.numFaces(); ++f) {
    auto fv = level.faceVerticesOf(f);
    surface.addPolygon(std::span<const int>(fv.data(), fv.size()));
  }
}

}  // namespace

SurfaceMesh polygonSurfaceOf(const Level& level, std::span<const Vec3> points) {
  SurfaceMesh surface;
  surface.positions.assign(points.begin(), points.begin() + level.numVertices);
  addPolygons(level, surface);
  return surface;
}

SurfaceMesh polygonControlSurfaceOf(const Level& level, std::span<const Vec3> points) {
  SurfaceMesh surface = polygonSurfaceOf(level, points);
  surface.normals = areaWeightedVertexNormals(surface.positions, surface.triangles);
  return surface;
}

Expected<SurfaceMesh> catmarkLimitSurfaceOf(const Level& level, const CreaseOptions& options,
                                            std::span<const Vec3> points) {
  SurfaceMesh surface;
  surface.positions.resize(level.numVertices);
  surface.normals.resize(level.numVertices);
  TESSERA_RETURN_IF_ERROR(computeCatmarkLimit(level, options, points, surface.positions, surface.normals));
  addPolygons(level, surface);
  return surface;
}

}  // namespace tessera
