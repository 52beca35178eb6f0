#include "core/catmark/polygon_level.h"

#include "core/topology/level_builder.h"

namespace tessera {

PolyTopology PolyTopology::fromBaseMesh(const BaseMesh& mesh) {
  // The same triangles and tags as the Loop scheme reads (BaseTopology).
  return fromTriangles(BaseTopology::fromBaseMesh(mesh));
}

PolyTopology PolyTopology::fromTriangles(BaseTopology base) {
  PolyTopology topology;
  topology.numVertices = base.numVertices;
  for (const auto& t : base.triangles) topology.addFace(t);
  topology.creases = std::move(base.creases);
  topology.vertexSharpness = std::move(base.vertexSharpness);
  return topology;
}

PolyTopology PolyTopology::fromSoup(const PolygonSoup& soup) {
  PolyTopology topology;
  topology.numVertices = static_cast<int>(soup.points.size());
  topology.faceOffsets.assign(soup.faceOffsets.begin(), soup.faceOffsets.end());
  topology.indices = soup.indices;
  return topology;
}

Expected<Level> buildPolyLevel(const PolyTopology& topology, const CreaseOptions& options) {
  topology::FaceRows faces;
  faces.numVertices = topology.numVertices;
  faces.offsets.assign(topology.faceOffsets.begin(), topology.faceOffsets.end());
  faces.corners.assign(topology.indices.begin(), topology.indices.end());
  TESSERA_ASSIGN_OR_RETURN(Level level, topology::buildLevel(std::move(faces)));
  TESSERA_RETURN_IF_ERROR(
      topology::applyTags(topology.creases, topology.vertexSharpness, options.boundary, level));
  return level;
}

}  // namespace tessera
