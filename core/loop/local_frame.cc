#include "core/loop/local_frame.h"

#include <cmath>
#include <numbers>

namespace tessera {

namespace {

// Tangents of the smooth rule for an interior ring: the first Fourier
// components of the neighbours, cos and sin of 2 pi k / n.
void smoothTangents(std::span<const Index> ring, std::span<const Vec3> p, Vec3& t1, Vec3& t2) {
  const int n = static_cast<int>(ring.size());
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    t1 += std::cos(a) * p[ring[k]];
    t2 += std::sin(a) * p[ring[k]];
  }
}

// Boundary: along the boundary (last to first neighbour) and across the
// faces, towards the mean of the other neighbours (or of the two boundary
// neighbours when the vertex has a single face). A frame only has to follow
// the surface, not be a limit tangent.
void boundaryTangents(Index v, std::span<const Index> ring, std::span<const Vec3> p, Vec3& t1, Vec3& t2) {
  const int n = static_cast<int>(ring.size());
  t1 = p[ring[0]] - p[ring[n - 1]];
  Vec3 inner(0, 0, 0);
  if (n > 2) {
    for (int k = 1; k < n - 1; ++k) inner += p[ring[k]];
    inner = (1.0 / (n - 2)) * inner;
  } else {
    inner = 0.5 * (p[ring[0]] + p[ring[1]]);
  }
  t2 = inner - p[v];
}

}  // namespace

LocalFrame localFrame(const Level& level, Index v, std::span<const Vec3> points) {
  auto ring = level.ringVerticesOf(v);
  Vec3 t1(0, 0, 0), t2(0, 0, 0);
  if (level.isBoundaryVertex(v)) {
    boundaryTangents(v, ring, points, t1, t2);
  } else {
    smoothTangents(ring, points, t1, t2);
  }
  const Vec3 n = t1 % t2;
  const Vec3 x = t1 - dot(t1, n) / std::max(n.sqrnorm(), 1e-300) * n;
  if (n.sqrnorm() <= 0.0 || x.sqrnorm() <= 0.0) return {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  LocalFrame frame;
  frame.normal = n.normalized();
  frame.tangent = x.normalized();
  frame.bitangent = frame.normal % frame.tangent;
  return frame;
}

}  // namespace tessera
