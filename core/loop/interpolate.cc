#include "core/loop/interpolate.h"

#include <cassert>
#include <vector>

#include "core/loop/masks.h"
#include "core/loop/refinement.h"

namespace tessera {

namespace {

// Vertex-vertex point for one rule (no blending). `smoothWeight[n]` is
// beta(n); ring sharpness is read only by the crease rule.
inline Vec3 vertexPointForRule(const Level& level, Index v, VertexRule rule, const float* ringSharpness,
                               std::span<const Vec3> p, const std::vector<double>& smoothWeight) {
  auto ring = level.ringVerticesOf(v);
  const int n = static_cast<int>(ring.size());
  switch (rule) {
    case VertexRule::kSmooth:
    case VertexRule::kDart: {
      const double w = smoothWeight[n];
      Vec3 sum(0, 0, 0);
      for (Index u : ring) sum += p[u];
      return (1.0 - n * w) * p[v] + w * sum;
    }
    case VertexRule::kCrease: {
      int ends[2];
      sharpEdgePair(std::span(ringSharpness, n), ends);
      return loop::kCreaseVertexWeight * p[v] + loop::kCreaseNeighbourWeight * (p[ring[ends[0]]] + p[ring[ends[1]]]);
    }
    case VertexRule::kCorner:
      return p[v];
  }
  return p[v];
}

void interpolateVertexPoints(const Level& parent, const Level& child, std::span<const Vec3> p,
                             std::span<Vec3> out) {
  const int maxValence = parent.maxValence;
  std::vector<double> smoothWeight(maxValence + 1, 0.0);
  for (int n = 3; n <= maxValence; ++n) smoothWeight[n] = loop::smoothEdgeWeight(n);
  std::vector<float> pSharp(maxValence), cSharp(maxValence);

  for (Index v = 0; v < parent.numVertices; ++v) {
    const VertexRule pRule = parent.vertexRules[v];
    if (isSmoothLike(pRule)) {
      // The common case: no sharpness to read, no blending.
      out[v] = vertexPointForRule(parent, v, pRule, nullptr, p, smoothWeight);
      continue;
    }
    parent.ringSharpness(v, pSharp.data());
    Vec3 point = vertexPointForRule(parent, v, pRule, pSharp.data(), p, smoothWeight);
    const VertexRule cRule = child.vertexRules[v];
    if (cRule != pRule) {
      // A semi-sharp feature ends at this level: blend the parent rule with
      // the child's by the fractional sharpness (Sdc, DeRose et al. '98).
      const int n = parent.valence(v);
      // The child's ring is the parent's, entry for entry: read the halves at v.
      int k = 0;
      for (Index e : parent.ringEdgesOf(v)) {
        cSharp[k++] = child.edgeSharpness[childEdgeAtEnd(parent, e, v)];
      }
      const double pw = fractionalWeightAtVertex(parent.vertexSharpness[v], child.vertexSharpness[v],
                                                 std::span(pSharp.data(), n), std::span(cSharp.data(), n));
      const Vec3 childRulePoint = vertexPointForRule(parent, v, cRule, cSharp.data(), p, smoothWeight);
      point = pw * point + (1.0 - pw) * childRulePoint;
    }
    out[v] = point;
  }
}

void interpolateEdgePoints(const Level& parent, const Level& child, std::span<const Vec3> p,
                           std::span<Vec3> out) {
  const Index nV = parent.numVertices;
  for (Index e = 0; e < parent.numEdges(); ++e) {
    const auto& ev = parent.edgeVertices[e];
    const float s = parent.edgeSharpness[e];
    const Vec3 ends = p[ev[0]] + p[ev[1]];
    if (isSharp(s) && child.vertexRules[nV + e] == VertexRule::kCrease) {
      out[nV + e] = 0.5 * ends;
      continue;
    }
    // Smooth (or crease decaying to smooth here): 3/8 ends + 1/8 opposite.
    const auto& ef = parent.edgeFaces[e];
    const auto& el = parent.edgeFaceLocal[e];
    assert(ef[1] != kInvalidIndex && "boundary edges are infinitely sharp");
    const Index oA = parent.faceVertices[ef[0]][(el[0] + 2) % 3];
    const Index oB = parent.faceVertices[ef[1]][(el[1] + 2) % 3];
    Vec3 point = loop::kEdgeEndWeight * ends + loop::kEdgeOppositeWeight * (p[oA] + p[oB]);
    if (isSharp(s)) {
      // Blend with the crease rule by the parent sharpness, as Sdc does
      // (its weight is the sharpness itself, which is < 1 here).
      const double pw = s;
      point = pw * (0.5 * ends) + (1.0 - pw) * point;
    }
    out[nV + e] = point;
  }
}

}  // namespace

void interpolateLevel(const Level& parent, const Level& child, std::span<const Vec3> parentPoints,
                      std::span<Vec3> childPoints) {
  assert(static_cast<int>(parentPoints.size()) >= parent.numVertices);
  assert(static_cast<int>(childPoints.size()) >= child.numVertices);
  interpolateVertexPoints(parent, child, parentPoints, childPoints);
  interpolateEdgePoints(parent, child, parentPoints, childPoints);
}

}  // namespace tessera
