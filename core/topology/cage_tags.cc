#include "core/topology/cage_tags.h"

#include "core/mesh/sharpness.h"

namespace tessera {

void addCageTags(const Level& level, SurfaceMesh& surface) {
  for (Index e = 0; e < static_cast<Index>(level.edgeVertices.size()); ++e) {
    if (!isSmooth(level.edgeSharpness[e]))
      surface.creases.push_back({level.edgeVertices[e][0], level.edgeVertices[e][1], level.edgeSharpness[e]});
  }
  for (Index v = 0; v < level.numVertices; ++v) {
    if (!isSmooth(level.vertexSharpness[v])) surface.corners.push_back({v, level.vertexSharpness[v]});
  }
}

}  // namespace tessera
