// Catmull-Clark's new points one at a time, with OpenSubdiv's Sdc rules for
// sharp and semi-sharp features (DeRose, Kass & Truong, "Subdivision
// Surfaces in Character Animation"): the uniform refinement
// (core/catmark/interpolate.cc) and the sparse hierarchy's stencils
// (stencils.h) both compute their points here, each supplying the face
// points and the child's rules and sharpness its own way. Forced inline:
// the uniform refinement runs them for every vertex and edge of a level,
// and as calls they cost it about 10 % more instructions (callgrind,
// fandisk to level 3).
#pragma once

#include <span>

#include "core/catmark/masks.h"
#include "core/loop/crease.h"
#include "core/topology/level.h"
#include "core/util/vec3.h"

namespace tessera::catmark {

// The point in face f: the centroid of its corners.
inline Vec3 facePoint(const Level& parent, Index f, std::span<const Vec3> p) {
  const Index from = parent.faceBegin(f), to = from + parent.faceSize(f);
  const Index* fv = parent.faceVertices.data();
  Vec3 sum = p[fv[from]];
  for (Index k = from + 1; k < to; ++k) sum += p[fv[k]];
  return facePointWeight(to - from) * sum;
}

// The point on parent edge e. `childRule` is the rule of the vertex the
// split puts on e; `faceOf(f)` gives the point in e's face f, read only
// where the smooth rule takes part.
template <typename FaceOf>
[[gnu::always_inline]] inline Vec3 edgePoint(const Level& parent, Index e, std::span<const Vec3> p,
                                             VertexRule childRule, const FaceOf& faceOf) {
  const auto& ev = parent.edgeVertices[e];
  const Vec3 ends = p[ev[0]] + p[ev[1]];
  const float s = parent.edgeSharpness[e];
  if (isSharp(s) && childRule == VertexRule::kCrease) return 0.5 * ends;
  const auto& ef = parent.edgeFaces[e];
  const Vec3 faces = faceOf(ef[0]) + faceOf(ef[1]);
  const Vec3 point = kEdgeFaceWeight * faces + kEdgeEndWeight * ends;
  if (!isSharp(s)) return point;
  // A crease decaying to smooth here: Sdc weighs the crease rule by the
  // parent sharpness itself (< 1 here, or Chaikin's > 1 edge whose halves
  // both became smooth).
  const double pw = s;
  return pw * (0.5 * ends) + (1.0 - pw) * point;
}

// The child of parent vertex v by one rule, no blending; the ring's
// sharpness is read by the crease rule alone.
template <typename FaceOf>
[[gnu::always_inline]] inline Vec3 vertexPointForRule(const Level& parent, Index v, VertexRule rule,
                                                      const float* ringSharpness, std::span<const Vec3> p,
                                                      const FaceOf& faceOf) {
  switch (rule) {
    case VertexRule::kSmooth:
    case VertexRule::kDart: {
      const Index from = parent.ringOffsets[v], to = parent.ringOffsets[v + 1];
      const int n = to - from;
      Vec3 sum(0, 0, 0);
      for (Index k = from; k < to; ++k) {
        sum += faceOf(parent.ringFaces[k]);
        sum += p[parent.ringVertices[k]];
      }
      return smoothNeighbourWeight(n) * sum + smoothVertexWeight(n) * p[v];
    }
    case VertexRule::kCrease: {
      auto ring = parent.ringVerticesOf(v);
      int ends[2];
      sharpEdgePair(std::span(ringSharpness, ring.size()), ends);
      return kCreaseNeighbourWeight * (p[ring[ends[0]]] + p[ring[ends[1]]]) + kCreaseVertexWeight * p[v];
    }
    case VertexRule::kCorner:
      return p[v];
  }
  return p[v];
}

// What a vertex's child is under: its rule and sharpness, and the
// sharpness of the half of each ring edge at it (`childHalf(k)`, ring
// order), read only where a semi-sharp feature ends at this level.
// `parentRing` and `childRing` are scratch of the vertex's valence.
template <typename FaceOf, typename ChildHalf>
[[gnu::always_inline]] inline Vec3 vertexPoint(const Level& parent, Index v, std::span<const Vec3> p,
                                               const FaceOf& faceOf, VertexRule childRule,
                                               float childSharpness, const ChildHalf& childHalf,
                                               float* parentRing, float* childRing) {
  const VertexRule pRule = parent.vertexRules[v];
  if (isSmoothLike(pRule)) return vertexPointForRule(parent, v, pRule, nullptr, p, faceOf);
  parent.ringSharpness(v, parentRing);
  const Vec3 point = vertexPointForRule(parent, v, pRule, parentRing, p, faceOf);
  if (childRule == pRule) return point;
  // A semi-sharp feature ends at this level: blend the two rules by the
  // fractional sharpness (Sdc's ComputeFractionalWeightAtVertex).
  const int n = parent.valence(v);
  for (int k = 0; k < n; ++k) childRing[k] = childHalf(k);
  const double pw = fractionalWeightAtVertex(parent.vertexSharpness[v], childSharpness,
                                             std::span(parentRing, n), std::span<const float>(childRing, n));
  const Vec3 childRulePoint = vertexPointForRule(parent, v, childRule, childRing, p, faceOf);
  return pw * point + (1.0 - pw) * childRulePoint;
}

}  // namespace tessera::catmark
