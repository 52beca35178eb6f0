#include "core/loop/interpolate.h"

#include <cassert>

#include "core/loop/masks.h"

namespace tessera {

LoopStencils::LoopStencils(const Level& parent, const LoopOptions& options)
    : parent_(parent),
      inherit_(parent, options),
      smoothWeight_(static_cast<size_t>(parent.maxValence) + 1, 0.0),
      parentSharpness_(static_cast<size_t>(parent.maxValence)),
      childSharpness_(static_cast<size_t>(parent.maxValence)) {
  for (int n = 3; n <= parent.maxValence; ++n) smoothWeight_[n] = loop::smoothEdgeWeight(n);
}

// One rule, no blending; ring sharpness is read only by the crease rule.
Vec3 LoopStencils::vertexPointForRule(Index v, VertexRule rule, const float* ringSharpness,
                                      std::span<const Vec3> p) const {
  auto ring = parent_.ringVerticesOf(v);
  const int n = static_cast<int>(ring.size());
  switch (rule) {
    case VertexRule::kSmooth:
    case VertexRule::kDart: {
      const double w = smoothWeight_[n];
      Vec3 sum(0, 0, 0);
      for (Index u : ring) sum += p[u];
      return (1.0 - n * w) * p[v] + w * sum;
    }
    case VertexRule::kCrease: {
      int ends[2];
      sharpEdgePair(std::span(ringSharpness, n), ends);
      return loop::kCreaseVertexWeight * p[v] +
             loop::kCreaseNeighbourWeight * (p[ring[ends[0]]] + p[ring[ends[1]]]);
    }
    case VertexRule::kCorner:
      return p[v];
  }
  return p[v];
}

Vec3 LoopStencils::vertexChild(Index v, std::span<const Vec3> p) {
  const VertexRule pRule = parent_.vertexRules[v];
  // The common case: no sharpness to read, no blending.
  if (isSmoothLike(pRule)) return vertexPointForRule(v, pRule, nullptr, p);
  parent_.ringSharpness(v, parentSharpness_.data());
  Vec3 point = vertexPointForRule(v, pRule, parentSharpness_.data(), p);
  const VertexRule cRule = inherit_.vertexChildRule(v);
  if (cRule == pRule) return point;
  // A semi-sharp feature ends at this level: blend the parent rule with the
  // child's by the fractional sharpness (Sdc, DeRose et al. '98).
  const int n = parent_.valence(v);
  int k = 0;
  for (Index e : parent_.ringEdgesOf(v)) {
    childSharpness_[k++] = inherit_.halfSharpness(e, parent_.edgeVertices[e][0] == v ? 0 : 1);
  }
  const double pw =
      fractionalWeightAtVertex(parent_.vertexSharpness[v], inherit_.vertexChildSharpness(v),
                               std::span(parentSharpness_.data(), n), std::span(childSharpness_.data(), n));
  const Vec3 childRulePoint = vertexPointForRule(v, cRule, childSharpness_.data(), p);
  return pw * point + (1.0 - pw) * childRulePoint;
}

Vec3 LoopStencils::edgeChild(Index e, std::span<const Vec3> p) {
  const auto& ev = parent_.edgeVertices[e];
  const float s = parent_.edgeSharpness[e];
  const Vec3 ends = p[ev[0]] + p[ev[1]];
  if (isSharp(s) && inherit_.edgeChildRule(e) == VertexRule::kCrease) return 0.5 * ends;
  // Smooth (or a crease decaying to smooth here): 3/8 ends + 1/8 opposite.
  const auto& ef = parent_.edgeFaces[e];
  const auto& el = parent_.edgeFaceLocal[e];
  assert(ef[0] >= 0 && ef[1] >= 0 && "boundary edges are infinitely sharp; absent faces are never refined");
  const Index oA = parent_.triangleVertices(ef[0])[(el[0] + 2) % 3];
  const Index oB = parent_.triangleVertices(ef[1])[(el[1] + 2) % 3];
  Vec3 point = loop::kEdgeEndWeight * ends + loop::kEdgeOppositeWeight * (p[oA] + p[oB]);
  if (isSharp(s)) {
    // Blend with the crease rule by the parent sharpness, as Sdc does (its
    // weight is the sharpness itself, which is < 1 here).
    const double pw = s;
    point = pw * (0.5 * ends) + (1.0 - pw) * point;
  }
  return point;
}

void interpolateLevel(const Level& parent, const LoopOptions& options, std::span<const Vec3> parentPoints,
                      std::span<Vec3> childPoints) {
  const Index nV = parent.numVertices;
  assert(static_cast<int>(parentPoints.size()) >= nV);
  assert(static_cast<int>(childPoints.size()) >= nV + parent.numEdges());
  LoopStencils stencils(parent, options);
  for (Index v = 0; v < nV; ++v) childPoints[v] = stencils.vertexChild(v, parentPoints);
  for (Index e = 0; e < parent.numEdges(); ++e) childPoints[nV + e] = stencils.edgeChild(e, parentPoints);
}

}  // namespace tessera
