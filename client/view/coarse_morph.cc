#include "client/view/coarse_morph.h"

#include <algorithm>
#include <unordered_map>

namespace tessera::view {

Expected<CoarseMorphBase> coarseMorphBase(const wire::MorphControl& c) {
  if (c.points_size() % 3 != 0) return invalidArgument("morph control: points are not x, y, z triples");
  const int vertices = c.points_size() / 3;
  if (c.triangles_size() == 0 || c.triangles_size() % 3 != 0) {
    return invalidArgument("morph control: no triangles, or not three indices each");
  }
  if (c.crease_vertices_size() != 2 * c.crease_sharpness_size()) {
    return invalidArgument("morph control: crease ends and sharpness disagree");
  }
  if (c.vertex_sharpness_size() != 0 && c.vertex_sharpness_size() != vertices) {
    return invalidArgument("morph control: vertex sharpness is not one per base vertex");
  }
  CoarseMorphBase base;
  base.topology.numVertices = vertices;
  for (int i = 0; i < c.triangles_size(); i += 3) {
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k) {
      if (c.triangles(i + k) >= static_cast<uint32_t>(vertices)) {
        return invalidArgument("morph control: triangle " + std::to_string(i / 3) + " names vertex " +
                               std::to_string(c.triangles(i + k)) + " of " + std::to_string(vertices));
      }
      t[k] = static_cast<int>(c.triangles(i + k));
    }
    base.topology.triangles.push_back(t);
  }
  for (int i = 0; i < c.crease_sharpness_size(); ++i) {
    base.topology.creases.push_back({static_cast<int>(c.crease_vertices(2 * i)),
                                     static_cast<int>(c.crease_vertices(2 * i + 1)), c.crease_sharpness(i)});
  }
  base.topology.vertexSharpness.assign(c.vertex_sharpness().begin(), c.vertex_sharpness().end());
  base.options.maxLevel = static_cast<int>(c.max_level());
  if (c.crease_method() == wire::CREASE_METHOD_CHAIKIN)
    base.options.loop.creaseMethod = CreaseMethod::kChaikin;
  if (c.boundary() == wire::BOUNDARY_INTERPOLATION_EDGE_AND_CORNER) {
    base.options.loop.boundary = BoundaryInterpolation::kEdgeAndCorner;
  }
  return base;
}

Expected<RegionMesh> refineCoarseMorph(const CoarseMorphBase& base, const wire::MorphControl& frame,
                                       int level) {
  if (frame.points_size() != 3 * base.topology.numVertices) {
    return invalidArgument("morph control: " + std::to_string(frame.points_size() / 3) + " points for " +
                           std::to_string(base.topology.numVertices) + " base vertices");
  }
  std::vector<Vec3> points;
  points.reserve(static_cast<size_t>(base.topology.numVertices));
  for (int i = 0; i < frame.points_size(); i += 3)
    points.emplace_back(frame.points(i), frame.points(i + 1), frame.points(i + 2));
  TESSERA_ASSIGN_OR_RETURN(Document doc, Document::create(base.topology, std::move(points), base.options));
  level = std::clamp(level, 0, base.options.maxLevel);
  TESSERA_ASSIGN_OR_RETURN(SurfaceMesh surface, doc.surface(level, SurfaceKind::kLimit));
  RegionMesh mesh;
  mesh.positions = std::move(surface.positions);
  mesh.normals = std::move(surface.normals);
  mesh.triangles = std::move(surface.triangles);
  // Vertices 0..n-1 are the level's; the crease copies after them sit
  // exactly where their original does (core/loop/surfaces.h).
  const uint64_t n = doc.counts().vertices(level);
  std::unordered_map<std::string, uint64_t> byPosition;
  mesh.vertexIds.resize(mesh.positions.size());
  for (uint64_t v = 0; v < mesh.positions.size(); ++v) {
    const std::string key(reinterpret_cast<const char*>(&mesh.positions[v]), sizeof(Vec3));
    if (v < n) {
      const VertexId id(level, v);
      mesh.vertexIds[v] = VertexId(doc.counts().birthLevel(id), v).packed();
      byPosition.emplace(key, mesh.vertexIds[v]);
    } else {
      auto it = byPosition.find(key);
      mesh.vertexIds[v] = it == byPosition.end() ? 0 : it->second;
    }
  }
  return mesh;
}

}  // namespace tessera::view
