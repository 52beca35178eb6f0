#include "core/loop/edge_child_limit.h"

#include "core/loop/masks.h"
#include "core/mesh/sharpness.h"

namespace tessera {

std::optional<Vec3> EdgeChildLimits::limit(Index e, std::span<const Vec3> points) {
  const float s = level_.edgeSharpness[e];
  if (isSharp(s) && !isInfinite(s)) return std::nullopt;
  const auto& ev = level_.edgeVertices[e];
  const Vec3 middle = stencils_.edgeChild(e, points);
  const Vec3 endChildren = stencils_.vertexChild(ev[0], points) + stencils_.vertexChild(ev[1], points);
  if (isInfinite(s)) {
    return loop::kCreaseLimitVertexWeight * middle + loop::kCreaseLimitNeighbourWeight * endChildren;
  }
  // Smooth: the ring is the ends' children and the vertices on the two
  // other edges of each of e's faces.
  Vec3 ring = endChildren;
  const auto& ef = level_.edgeFaces[e];
  const auto& el = level_.edgeFaceLocal[e];
  for (int side = 0; side < 2; ++side) {
    const auto fe = level_.triangleEdges(ef[side]);
    ring += stencils_.edgeChild(fe[(el[side] + 1) % 3], points);
    ring += stencils_.edgeChild(fe[(el[side] + 2) % 3], points);
  }
  return 0.5 * middle + loop::smoothLimitEdgeWeight(6) * ring;
}

}  // namespace tessera
