#include "core/loop/limit.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "core/loop/exact_limit.h"
#include "core/loop/masks.h"

namespace tessera {

namespace detail {

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

}  // namespace detail

namespace {

using detail::SmoothTables;

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

LimitFrame frameWith(const Level& level, Index v, std::span<const Vec3> points, const SmoothTables& tables,
                     CreaseMethod method, const FarRingSharpness* far) {
  // A smooth vertex's ring has no sharp edge, so its closed-form masks are
  // exact; every other rule goes through its ring's eigenstructure.
  if (level.vertexRules[v] == VertexRule::kSmooth) return smoothFrame(level, v, points, tables);
  return exactVertexLimit(level, v, points, method, false, far).frame;
}

}  // namespace

std::vector<LimitSector> otherLimitSectors(const Level& level, Index v, std::span<const Vec3> points,
                                           CreaseMethod method, const FarRingSharpness* far) {
  if (isSmoothLike(level.vertexRules[v])) return {};
  return exactVertexLimit(level, v, points, method, true, far).others;
}

int limitSideOfRingFace(const Level& level, Index v, int ringFace) {
  if (isSmoothLike(level.vertexRules[v])) return 0;
  const std::vector<int> sharp = sharpRingEdges(level, v);
  const int m = static_cast<int>(sharp.size());
  if (m < 2) return 0;
  // Sector i runs from sharp edge i to sharp edge i + 1; the last wraps
  // past ring edge 0 (ring faces before the first sharp edge lie in it).
  int sector = m - 1;
  for (int i = 0; i < m && sharp[i] <= ringFace; ++i) sector = i;
  // As otherLimitSectors() numbers them: the primary sector first, then
  // the others in ring order (a boundary's wrap, the last, has no faces).
  const int primary = (level.vertexRules[v] == VertexRule::kCrease || sharp[0] == 0) ? 0 : m - 1;
  if (sector == primary) return 0;
  return sector < primary ? sector + 1 : sector;
}

LimitFrame limitFrame(const Level& level, Index v, std::span<const Vec3> points, CreaseMethod method,
                      const FarRingSharpness* far) {
  SmoothTables tables(level.valence(v));
  return frameWith(level, v, points, tables, method, far);
}

LimitEvaluator::LimitEvaluator(const Level& level, CreaseMethod method, const FarRingSharpness* far)
    : level_(level),
      method_(method),
      far_(far),
      tables_(std::make_unique<const SmoothTables>(level.maxValence)) {}

LimitEvaluator::~LimitEvaluator() = default;

LimitFrame LimitEvaluator::frame(Index v, std::span<const Vec3> points) const {
  return frameWith(level_, v, points, *tables_, method_, far_);
}

void computeLimit(const Level& level, std::span<const Vec3> points, std::span<Vec3> positions,
                  std::span<Vec3> normals, CreaseMethod method) {
  const SmoothTables tables(level.maxValence);
  const bool wantNormals = !normals.empty();
  for (Index v = 0; v < level.numVertices; ++v) {
    if (level.vertexRules[v] != VertexRule::kSmooth) {
      // No frame to build: the sector's normal is what is written.
      Vec3 normal;
      exactLimitPositionAndNormal(level, v, points, method, positions[v], normal);
      if (wantNormals) normals[v] = normal;
      continue;
    }
    const LimitFrame frame = smoothFrame(level, v, points, tables);
    positions[v] = frame.position;
    if (wantNormals) normals[v] = frame.normal();
  }
}

}  // namespace tessera
