#include "core/loop/limit.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "core/loop/masks.h"

namespace tessera {

namespace {

// Per-valence smooth limit weights and tangent coefficients, computed once
// per evaluation instead of once per vertex.
class SmoothTables {
 public:
  explicit SmoothTables(int maxValence) : offsets_(maxValence + 2, 0), weight_(maxValence + 1, 0.0) {
    for (int n = 0; n <= maxValence; ++n) offsets_[n + 1] = offsets_[n] + n;
    cos_.resize(offsets_.back());
    sin_.resize(offsets_.back());
    for (int n = 3; n <= maxValence; ++n) {
      weight_[n] = loop::smoothLimitEdgeWeight(n);
      // The first Fourier components of the ring: cos, sin of 2 pi k / n.
      for (int k = 0; k < n; ++k) {
        cos_[offsets_[n] + k] = std::cos(2.0 * std::numbers::pi * k / n);
        sin_[offsets_[n] + k] = std::sin(2.0 * std::numbers::pi * k / n);
      }
    }
  }
  double weight(int n) const { return weight_[n]; }
  const double* cos(int n) const { return cos_.data() + offsets_[n]; }
  const double* sin(int n) const { return sin_.data() + offsets_[n]; }

 private:
  std::vector<int> offsets_;
  std::vector<double> weight_, cos_, sin_;
};

// The regular case, valence 6, with its weights written out: cos(k pi/3) is
// +-1 or +-1/2 and sin(k pi/3) is 0 or +-sqrt(3)/2 (loopScheme.h does the same).
LimitFrame regularFrame(std::span<const Index> ring, Index v, std::span<const Vec3> p) {
  const Vec3 &q0 = p[ring[0]], &q1 = p[ring[1]], &q2 = p[ring[2]];
  const Vec3 &q3 = p[ring[3]], &q4 = p[ring[4]], &q5 = p[ring[5]];
  constexpr double kRoot3By2 = 0.86602540378443864676;
  const Vec3 sum = (q0 + q1) + (q2 + q3) + (q4 + q5);
  return {0.5 * p[v] + (1.0 / 12.0) * sum, (q0 - q3) + 0.5 * ((q1 + q5) - (q2 + q4)),
          kRoot3By2 * ((q1 + q2) - (q4 + q5))};
}

LimitFrame smoothFrame(const Level& level, Index v, std::span<const Vec3> p, const SmoothTables& tables) {
  auto ring = level.ringVerticesOf(v);
  const int n = static_cast<int>(ring.size());
  if (n == 6) return regularFrame(ring, v, p);
  const double* c = tables.cos(n);
  const double* s = tables.sin(n);
  Vec3 sum(0, 0, 0), t1(0, 0, 0), t2(0, 0, 0);
  for (int k = 0; k < n; ++k) {
    const Vec3& q = p[ring[k]];
    sum += q;
    t1 += c[k] * q;
    t2 += s[k] * q;
  }
  const double w = tables.weight(n);
  return {(1.0 - n * w) * p[v] + w * sum, t1, t2};
}

LimitFrame creaseFrame(const Level& level, Index v, std::span<const Vec3> p) {
  auto ring = level.ringVerticesOf(v);
  const int n = static_cast<int>(ring.size());
  std::vector<float> sharpness(n);
  level.ringSharpness(v, sharpness.data());
  int ends[2];
  sharpEdgePair(sharpness, ends);
  auto neighbour = [&](int k) -> const Vec3& { return p[ring[k]]; };

  LimitFrame frame{Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 0)};
  frame.position = loop::kCreaseLimitVertexWeight * p[v] +
                   loop::kCreaseLimitNeighbourWeight * (neighbour(ends[0]) + neighbour(ends[1]));
  // Along the crease, scaled by 3/2 to match interior tangent magnitudes.
  frame.tangent1 = 1.5 * (neighbour(ends[0]) - neighbour(ends[1]));

  // Across the span of faces from ends[0] to ends[1] (Hoppe et al. '94 /
  // Biermann et al. boundary masks, oriented inward as OpenSubdiv does).
  const int interior = ends[1] - ends[0] - 1;
  Vec3& t2 = frame.tangent2;
  if (interior == 0) {
    t2 = -6.0 * p[v] + 3.0 * (neighbour(ends[0]) + neighbour(ends[1]));
  } else if (interior == 1) {
    t2 = -3.0 * p[v] + 3.0 * neighbour(ends[0] + 1);
  } else if (interior == 2) {
    const double r3 = std::sqrt(3.0);
    t2 = -r3 * p[v] - 0.5 * r3 * (neighbour(ends[0]) + neighbour(ends[1])) +
         r3 * (neighbour(ends[0] + 1) + neighbour(ends[0] + 2));
  } else {
    const double theta = std::numbers::pi / (interior + 1);
    const double cw = -3.0 * std::sin(theta);
    const double ew = -3.0 * (2.0 * std::cos(theta) - 2.0);
    t2 = cw * (neighbour(ends[0]) + neighbour(ends[1]));
    for (int i = 1; i <= interior; ++i) t2 += ew * std::sin(i * theta) * neighbour(ends[0] + i);
  }
  return frame;
}

LimitFrame cornerFrame(const Level& level, Index v, std::span<const Vec3> p) {
  auto ring = level.ringVerticesOf(v);
  // Differences to the first two ring neighbours, scaled by 3 (OpenSubdiv's
  // magnitude convention): the tangent plane of the first face's sector.
  return {p[v], 3.0 * (p[ring[0]] - p[v]), 3.0 * (p[ring[1]] - p[v])};
}

LimitFrame frameWith(const Level& level, Index v, std::span<const Vec3> points, const SmoothTables& tables) {
  switch (level.vertexRules[v]) {
    case VertexRule::kSmooth:
    case VertexRule::kDart:
      return smoothFrame(level, v, points, tables);
    case VertexRule::kCrease:
      return creaseFrame(level, v, points);
    case VertexRule::kCorner:
      return cornerFrame(level, v, points);
  }
  return cornerFrame(level, v, points);
}

}  // namespace

LimitFrame limitFrame(const Level& level, Index v, std::span<const Vec3> points) {
  SmoothTables tables(level.valence(v));
  return frameWith(level, v, points, tables);
}

void computeLimit(const Level& level, std::span<const Vec3> points, std::span<Vec3> positions,
                  std::span<Vec3> normals) {
  const SmoothTables tables(level.maxValence);
  const bool wantNormals = !normals.empty();
  for (Index v = 0; v < level.numVertices; ++v) {
    if (!wantNormals && isSmoothLike(level.vertexRules[v])) {
      auto ring = level.ringVerticesOf(v);
      const int n = static_cast<int>(ring.size());
      const double w = tables.weight(n);
      Vec3 sum(0, 0, 0);
      for (Index u : ring) sum += points[u];
      positions[v] = (1.0 - n * w) * points[v] + w * sum;
      continue;
    }
    const LimitFrame frame = frameWith(level, v, points, tables);
    positions[v] = frame.position;
    if (wantNormals) normals[v] = frame.normal();
  }
}

}  // namespace tessera
