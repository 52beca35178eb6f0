#include "core/topology/tags.h"

#include <string>

namespace tessera::topology {

namespace {

std::string edgeName(int a, int b) {
  return "edge " + std::to_string(a) + "-" + std::to_string(b);
}

Index findEdge(const Level& level, Index a, Index b) {
  for (Index e : level.ringEdgesOf(a)) {
    if (level.otherVertex(e, a) == b) return e;
  }
  return kNoIndex;
}

}  // namespace

float heldVertexSharpness(const Level& level, Index v, float tagged, BoundaryInterpolation boundary) {
  const bool topologicalCorner = level.isBoundaryVertex(v) && level.valence(v) == 2;
  if (boundary == BoundaryInterpolation::kEdgeAndCorner && topologicalCorner) return kSharpnessInfinite;
  return canonicalSharpness(tagged);
}

Status applyTags(std::span<const Crease> creases, std::span<const float> vertexSharpness,
                 BoundaryInterpolation boundary, Level& level) {
  const int nV = level.numVertices;
  level.edgeSharpness.assign(level.numEdges(), kSharpnessSmooth);
  level.vertexSharpness.assign(nV, kSharpnessSmooth);
  for (size_t i = 0; i < creases.size(); ++i) {
    const Crease& c = creases[i];
    const std::string crease = "crease " + std::to_string(i);
    if (c.v0 < 0 || c.v0 >= nV || c.v1 < 0 || c.v1 >= nV) {
      return notFound(crease + " names " + edgeName(c.v0, c.v1) + ", a vertex outside 0.." +
                      std::to_string(nV - 1));
    }
    const Index e = findEdge(level, c.v0, c.v1);
    if (e == kNoIndex) {
      return notFound(crease + ": " + edgeName(c.v0, c.v1) + " does not exist: vertices " +
                      std::to_string(c.v0) + " and " + std::to_string(c.v1) + " share no edge");
    }
    level.edgeSharpness[e] = canonicalSharpness(c.sharpness);
  }
  if (!vertexSharpness.empty()) {
    if (static_cast<int>(vertexSharpness.size()) != nV) {
      return invalidArgument("vertex sharpness given for " + std::to_string(vertexSharpness.size()) +
                             " vertices, the mesh has " + std::to_string(nV));
    }
  }
  for (Index v = 0; v < nV; ++v) {
    level.vertexSharpness[v] = heldVertexSharpness(
        level, v, vertexSharpness.empty() ? kSharpnessSmooth : vertexSharpness[v], boundary);
  }
  for (Index e = 0; e < level.numEdges(); ++e) {
    if (level.isBoundaryEdge(e)) level.edgeSharpness[e] = kSharpnessInfinite;
  }
  level.recomputeVertexRules();
  return Status::ok();
}

}  // namespace tessera::topology
