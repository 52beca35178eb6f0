#include "core/loop/direct_manipulation.h"

#include "core/loop/limit.h"
#include "core/loop/masks.h"

namespace tessera {

double selfLimitWeight(const Level& level, Index v) {
  switch (level.vertexRules[v]) {
    case VertexRule::kSmooth:
    case VertexRule::kDart: {
      const int n = level.valence(v);
      return 1.0 - n * loop::smoothLimitEdgeWeight(n);
    }
    case VertexRule::kCrease:
      return loop::kCreaseLimitVertexWeight;
    case VertexRule::kCorner:
      return 1.0;
  }
  return 1.0;
}

Vec3 solveControlPoint(const Level& level, Index v, std::span<const Vec3> points, const Vec3& target) {
  const Vec3 current = limitFrame(level, v, points).position;
  return points[v] + (1.0 / selfLimitWeight(level, v)) * (target - current);
}

}  // namespace tessera
