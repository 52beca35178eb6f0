#include "core/render/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessera {

// By the Voronoi regions of the corners, edges and face (Ericson,
// Real-Time Collision Detection, 5.1.5).
Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab | ap, d2 = ac | ap;
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab | bp, d4 = ac | bp;
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab | cp, d6 = ac | cp;
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double sum = va + vb + vc;
  if (!(sum > 0)) return a;  // a degenerate triangle: its corner will do
  return a + (vb / sum) * ab + (vc / sum) * ac;
}

namespace {

constexpr int kMaxCells = 1 << 22;

}  // namespace

NearestTriangle::NearestTriangle(const MeshView& mesh, const Vec3& lo, const Vec3& hi)
    : mesh_(mesh), lo_(lo) {
  double edges = 0;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) edges += (mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]).norm();
  const Vec3 extent = hi - lo;
  cell_ =
      mesh.triangles.empty() ? extent.max() + 1 : std::max(2 * edges / (3.0 * mesh.triangles.size()), 1e-12);
  for (;;) {
    for (int k = 0; k < 3; ++k) dims_[k] = static_cast<int>(std::floor(extent[k] / cell_)) + 1;
    if (static_cast<int64_t>(dims_[0]) * dims_[1] * dims_[2] <= kMaxCells) break;
    cell_ *= 1.5;
  }
  const size_t cells = static_cast<size_t>(dims_[0]) * dims_[1] * dims_[2];
  std::vector<int> count(cells + 1, 0);
  auto forCells = [&](const std::array<int, 3>& t, auto&& f) {
    Vec3 a = mesh.positions[t[0]], b = a;
    for (int k = 1; k < 3; ++k) a.minimize(mesh.positions[t[k]]), b.maximize(mesh.positions[t[k]]);
    for (int z = cellOf(a[2], 2); z <= cellOf(b[2], 2); ++z)
      for (int y = cellOf(a[1], 1); y <= cellOf(b[1], 1); ++y)
        for (int x = cellOf(a[0], 0); x <= cellOf(b[0], 0); ++x) f(cellIndex(x, y, z));
  };
  for (const auto& t : mesh.triangles) forCells(t, [&](int c) { ++count[c + 1]; });
  for (size_t c = 0; c < cells; ++c) count[c + 1] += count[c];
  start_ = count;
  items_.resize(static_cast<size_t>(count[cells]));
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    forCells(mesh.triangles[i], [&](int c) { items_[count[c]++] = static_cast<int>(i); });
}

int NearestTriangle::cellOf(double t, int axis) const {
  return std::clamp(static_cast<int>(std::floor((t - lo_[axis]) / cell_)), 0, dims_[axis] - 1);
}

double NearestTriangle::distance(const Vec3& p) const {
  const int cx = cellOf(p[0], 0), cy = cellOf(p[1], 1), cz = cellOf(p[2], 2);
  double best2 = std::numeric_limits<double>::infinity();
  const int maxR = std::max({dims_[0], dims_[1], dims_[2]});
  for (int r = 0; r <= maxR; ++r) {
    for (int z = std::max(cz - r, 0); z <= std::min(cz + r, dims_[2] - 1); ++z) {
      for (int y = std::max(cy - r, 0); y <= std::min(cy + r, dims_[1] - 1); ++y) {
        for (int x = std::max(cx - r, 0); x <= std::min(cx + r, dims_[0] - 1); ++x) {
          if (std::max({std::abs(x - cx), std::abs(y - cy), std::abs(z - cz)}) != r) continue;
          const int c = cellIndex(x, y, z);
          for (int i = start_[c]; i < start_[c + 1]; ++i) {
            const auto& t = mesh_.triangles[items_[i]];
            const Vec3 q =
                closestOnTriangle(p, mesh_.positions[t[0]], mesh_.positions[t[1]], mesh_.positions[t[2]]);
            best2 = std::min(best2, (q - p).sqrnorm());
          }
        }
      }
    }
    // p lies in cell (cx, cy, cz): whatever the searched block misses is at
    // least r cells away.
    if (best2 <= (r * cell_) * (r * cell_)) break;
  }
  return std::sqrt(best2);
}

SurfaceDistance surfaceDistance(const MeshView& approximation, const MeshView& reference) {
  Vec3 lo(std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (const MeshView* m : {&approximation, &reference})
    for (const Vec3& p : m->positions) lo.minimize(p), hi.maximize(p);
  SurfaceDistance out;
  if (approximation.triangles.empty() || reference.triangles.empty()) return out;
  const NearestTriangle toReference(reference, lo, hi), toApproximation(approximation, lo, hi);
  double sum = 0, area = 0;
  for (const auto& t : approximation.triangles) {
    const Vec3 &a = approximation.positions[t[0]], &b = approximation.positions[t[1]],
               &c = approximation.positions[t[2]];
    const double w = 0.5 * ((b - a) % (c - a)).norm() / 10.0;
    for (int i = 0; i <= 3; ++i) {
      for (int j = 0; i + j <= 3; ++j) {
        const Vec3 p = (i / 3.0) * a + (j / 3.0) * b + ((3 - i - j) / 3.0) * c;
        const double d = toReference.distance(p);
        sum += w * d * d;
        out.max = std::max(out.max, d);
      }
    }
    area += 10 * w;
  }
  out.rms = area > 0 ? std::sqrt(sum / area) : 0;
  for (const Vec3& p : reference.positions) out.max = std::max(out.max, toApproximation.distance(p));
  return out;
}

}  // namespace tessera
