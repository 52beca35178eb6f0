#include "core/loop/level_builder.h"

#include "core/topology/level_builder.h"

namespace tessera {

BaseTopology BaseTopology::fromBaseMesh(const BaseMesh& mesh) {
  BaseTopology topology;
  topology.numVertices = mesh.numVertices();
  topology.triangles = mesh.faceVertexIndices();
  const TriMesh& m = mesh.mesh();
  for (auto eh : m.edges()) {
    float s = mesh.edgeSharpness(eh);
    if (isSharp(s)) {
      auto heh = m.halfedge_handle(eh, 0);
      topology.creases.push_back({m.from_vertex_handle(heh).idx(), m.to_vertex_handle(heh).idx(), s});
    }
  }
  topology.vertexSharpness.resize(topology.numVertices);
  for (auto vh : m.vertices()) topology.vertexSharpness[vh.idx()] = mesh.vertexSharpness(vh);
  return topology;
}

Expected<Level> buildBaseLevel(const BaseTopology& topology, const LoopOptions& options) {
  topology::FaceRows faces;
  faces.numVertices = topology.numVertices;
  faces.regularSize = 3;
  faces.corners.resize(3 * topology.triangles.size());
  for (size_t f = 0; f < topology.triangles.size(); ++f) {
    for (int j = 0; j < 3; ++j) faces.corners[3 * f + j] = topology.triangles[f][j];
  }
  TESSERA_ASSIGN_OR_RETURN(Level level, topology::buildLevel(std::move(faces)));
  TESSERA_RETURN_IF_ERROR(
      topology::applyTags(topology.creases, topology.vertexSharpness, options.boundary, level));
  return level;
}

}  // namespace tessera
