#include "core/loop/edge_child_limit.h"

#include "core/loop/masks.h"
#include "core/mesh/sharpness.h"

namespace tessera {

const Vec3& EdgeChildLimits::edgeChild(Index e) {
  auto [it, fresh] = edgeChildren_.try_emplace(e);
  if (fresh) it->second = stencils_.edgeChild(e, points_);
  return it->second;
}

const Vec3& EdgeChildLimits::vertexChild(Index v) {
  auto [it, fresh] = vertexChildren_.try_emplace(v);
  if (fresh) it->second = stencils_.vertexChild(v, points_);
  return it->second;
}

std::optional<Vec3> EdgeChildLimits::limit(Index e) {
  const float s = level_.edgeSharpness[e];
  if (isSharp(s) && !isInfinite(s)) return std::nullopt;
  const auto& ev = level_.edgeVertices[e];
  const Vec3 middle = edgeChild(e);
  const Vec3 endChildren = vertexChild(ev[0]) + vertexChild(ev[1]);
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
    ring += edgeChild(fe[(el[side] + 1) % 3]);
    ring += edgeChild(fe[(el[side] + 2) % 3]);
  }
  return 0.5 * middle + loop::smoothLimitEdgeWeight(6) * ring;
}

}  // namespace tessera
