#include "core/loop/direct_manipulation.h"

#include "core/loop/exact_limit.h"
#include "core/loop/limit.h"
#include "core/loop/masks.h"

namespace tessera {

double selfLimitWeight(const Level& level, Index v, CreaseMethod method, const FarRingSharpness* far) {
  if (level.vertexRules[v] == VertexRule::kSmooth) {
    const int n = level.valence(v);
    return 1.0 - n * loop::smoothLimitEdgeWeight(n);
  }
  // The points do not change the weight: the masks depend on the rules only.
  std::vector<Vec3> zeros(level.numVertices);
  return exactVertexLimit(level, v, zeros, method, false, far).selfWeight;
}

Vec3 solveControlPoint(const Level& level, Index v, std::span<const Vec3> points, const Vec3& target,
                       CreaseMethod method, const FarRingSharpness* far) {
  if (level.vertexRules[v] == VertexRule::kSmooth) {
    const Vec3 current = limitFrame(level, v, points, method).position;
    return points[v] + (1.0 / selfLimitWeight(level, v, method)) * (target - current);
  }
  const VertexLimit limit = exactVertexLimit(level, v, points, method, false, far);
  return points[v] + (1.0 / limit.selfWeight) * (target - limit.position);
}

}  // namespace tessera
