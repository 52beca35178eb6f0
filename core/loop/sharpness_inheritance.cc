#include "core/loop/sharpness_inheritance.h"

namespace tessera {

SharpnessInheritance::SharpnessInheritance(const Level& parent, const LoopOptions& options)
    : parent_(parent), method_(options.creaseMethod), ring_(static_cast<size_t>(parent.maxValence)) {}

float SharpnessInheritance::halfSharpness(Index e, int end) {
  const float s = parent_.edgeSharpness[e];
  if (isSmooth(s)) return kSharpnessSmooth;
  if (method_ != CreaseMethod::kChaikin || !isSemiSharp(s)) return decrementSharpness(s);
  const Index x = parent_.edgeVertices[e][end];
  parent_.ringSharpness(x, ring_.data());
  return subdivideEdgeSharpnessAtVertex(method_, s, std::span(ring_.data(), parent_.valence(x)));
}

VertexRule SharpnessInheritance::vertexChildRule(Index v) {
  // Sharpness never grows, so a smooth vertex has a smooth child.
  if (parent_.vertexRules[v] == VertexRule::kSmooth) return VertexRule::kSmooth;
  int sharpEdges = 0;
  for (Index e : parent_.ringEdgesOf(v)) {
    sharpEdges += isSharp(halfSharpness(e, parent_.edgeVertices[e][0] == v ? 0 : 1)) ? 1 : 0;
  }
  return vertexRule(vertexChildSharpness(v), sharpEdges);
}

VertexRule SharpnessInheritance::edgeChildRule(Index e) {
  if (isSmooth(parent_.edgeSharpness[e])) return VertexRule::kSmooth;
  const int sharpHalves = (isSharp(halfSharpness(e, 0)) ? 1 : 0) + (isSharp(halfSharpness(e, 1)) ? 1 : 0);
  return vertexRule(kSharpnessSmooth, sharpHalves);
}

}  // namespace tessera
