#include "core/schemes/catmark_interpolate.h"

#include <cassert>
#include <vector>

#include "core/loop/crease.h"
#include "core/schemes/catmark_masks.h"

namespace tessera::schemes {

namespace {

class CatmarkStencils {
 public:
  CatmarkStencils(const Level& parent, const Level& child, std::span<const Vec3> p, std::span<Vec3> c)
      : parent_(parent),
        child_(child),
        p_(p),
        c_(c),
        corners_(static_cast<Index>(parent.faceVertices.size())),
        firstFaceVertex_(parent.numVertices),
        parentSharpness_(parent.maxValence),
        childSharpness_(parent.maxValence) {}

  void facePoints() const {
    for (Index f = 0, nF = parent_.numFaces(); f < nF; ++f) {
      const Index from = parent_.faceBegin(f), to = from + parent_.faceSize(f);
      const Index* fv = parent_.faceVertices.data();
      Vec3 sum = p_[fv[from]];
      for (Index k = from + 1; k < to; ++k) sum += p_[fv[k]];
      c_[firstFaceVertex_ + f] = catmark::facePointWeight(to - from) * sum;
    }
  }

  void edgePoints() const {
    const Index first = parent_.numVertices + parent_.numFaces();
    for (Index e = 0, nE = static_cast<Index>(parent_.edgeVertices.size()); e < nE; ++e) {
      const auto& ev = parent_.edgeVertices[e];
      const Vec3 ends = p_[ev[0]] + p_[ev[1]];
      const float s = parent_.edgeSharpness[e];
      if (isSharp(s) && child_.vertexRules[first + e] == VertexRule::kCrease) {
        c_[first + e] = 0.5 * ends;
        continue;
      }
      const auto& ef = parent_.edgeFaces[e];
      assert(ef[1] != kNoIndex && "boundary edges are infinitely sharp");
      const Vec3 faces = c_[firstFaceVertex_ + ef[0]] + c_[firstFaceVertex_ + ef[1]];
      Vec3 point = catmark::kEdgeFaceWeight * faces + catmark::kEdgeEndWeight * ends;
      if (isSharp(s)) {
        // A crease decaying to smooth here: Sdc weighs the crease rule by
        // the parent sharpness itself (< 1 here, or Chaikin's > 1 edge whose
        // halves both became smooth).
        const double pw = s;
        point = pw * (0.5 * ends) + (1.0 - pw) * point;
      }
      c_[first + e] = point;
    }
  }

  void vertexPoints() {
    for (Index v = 0; v < parent_.numVertices; ++v) c_[v] = vertexPoint(v);
  }

 private:
  Vec3 smoothPoint(Index v) const {
    const Index from = parent_.ringOffsets[v], to = parent_.ringOffsets[v + 1];
    const int n = to - from;
    Vec3 sum(0, 0, 0);
    for (Index k = from; k < to; ++k) {
      sum += c_[firstFaceVertex_ + parent_.ringFaces[k]];
      sum += p_[parent_.ringVertices[k]];
    }
    return catmark::smoothNeighbourWeight(n) * sum + catmark::smoothVertexWeight(n) * p_[v];
  }

  Vec3 pointForRule(Index v, VertexRule rule, const float* ringSharpness) const {
    switch (rule) {
      case VertexRule::kSmooth:
      case VertexRule::kDart:
        return smoothPoint(v);
      case VertexRule::kCrease: {
        auto ring = parent_.ringVerticesOf(v);
        int ends[2];
        sharpEdgePair(std::span(ringSharpness, ring.size()), ends);
        return catmark::kCreaseNeighbourWeight * (p_[ring[ends[0]]] + p_[ring[ends[1]]]) +
               catmark::kCreaseVertexWeight * p_[v];
      }
      case VertexRule::kCorner:
        return p_[v];
    }
    return p_[v];
  }

  Vec3 vertexPoint(Index v) {
    const VertexRule pRule = parent_.vertexRules[v];
    if (isSmoothLike(pRule)) return smoothPoint(v);
    parent_.ringSharpness(v, parentSharpness_.data());
    const Vec3 point = pointForRule(v, pRule, parentSharpness_.data());
    const VertexRule cRule = child_.vertexRules[v];
    if (cRule == pRule) return point;
    // A semi-sharp feature ends at this level: blend the two rules by the
    // fractional sharpness (Sdc's ComputeFractionalWeightAtVertex).
    const int n = parent_.valence(v);
    auto ringEdges = parent_.ringEdgesOf(v);
    for (int k = 0; k < n; ++k) {
      const Index e = ringEdges[k];
      childSharpness_[k] = child_.edgeSharpness[corners_ + 2 * e + (parent_.edgeVertices[e][0] == v ? 0 : 1)];
    }
    const double pw =
        fractionalWeightAtVertex(parent_.vertexSharpness[v], child_.vertexSharpness[v],
                                 std::span(parentSharpness_.data(), n), std::span(childSharpness_.data(), n));
    const Vec3 childRulePoint = pointForRule(v, cRule, childSharpness_.data());
    return pw * point + (1.0 - pw) * childRulePoint;
  }

  const Level& parent_;
  const Level& child_;
  std::span<const Vec3> p_;
  std::span<Vec3> c_;
  const Index corners_;
  const Index firstFaceVertex_;
  std::vector<float> parentSharpness_, childSharpness_;
};

}  // namespace

void interpolateCatmark(const Level& parent, const Level& child, std::span<const Vec3> parentPoints,
                        std::span<Vec3> childPoints) {
  assert(static_cast<int>(childPoints.size()) >= child.numVertices);
  CatmarkStencils stencils(parent, child, parentPoints, childPoints);
  stencils.facePoints();
  stencils.edgePoints();
  stencils.vertexPoints();
}

}  // namespace tessera::schemes
