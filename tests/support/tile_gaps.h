// Gaps in an assembled set of tiles (docs/VIEWS.md "Assembling tiles"):
// boundary edges of one tile that lie on no boundary edge of another (the
// other's edge may be finer or coarser: either lies on the other), to
// 1e-12 of the model's size. Zero means watertight, for a closed surface.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <vector>

#include "core/tessellation/region_codec.h"

namespace tessera::testing {

inline Vec3 min(const Vec3& a, const Vec3& b) {
  return {std::min(a[0], b[0]), std::min(a[1], b[1]), std::min(a[2], b[2])};
}
inline Vec3 max(const Vec3& a, const Vec3& b) {
  return {std::max(a[0], b[0]), std::max(a[1], b[1]), std::max(a[2], b[2])};
}

// Boundary edges of the assembled tiles that lie on no other tile's
// boundary edge: gaps. Segments are indexed in a grid of cells.
// `onSurfaceBoundary(a, b)`, when given, names the tile edges (by their
// vertices' packed ids) that lie on the surface's own boundary: those have
// no other tile to meet and are not gaps.
inline int64_t unmatchedEdges(const std::vector<const RegionMesh*>& tiles,
                              const std::vector<std::vector<Vec3>>& positions, double scale,
                              const std::function<bool(uint64_t, uint64_t)>& onSurfaceBoundary = nullptr) {
  struct Segment {
    Vec3 a, b;
    size_t tile;
  };
  std::vector<Segment> segments;
  for (size_t i = 0; i < tiles.size(); ++i) {
    std::map<std::pair<uint64_t, uint64_t>, std::pair<int, std::array<int, 2>>> uses;
    const RegionMesh& m = *tiles[i];
    for (const auto& t : m.triangles) {
      for (int k = 0; k < 3; ++k) {
        int p = t[k], q = t[(k + 1) % 3];
        uint64_t a = m.vertexIds[p], b = m.vertexIds[q];
        if (a > b) std::swap(a, b), std::swap(p, q);
        auto& u = uses[{a, b}];
        ++u.first;
        u.second = {p, q};
      }
    }
    for (const auto& [e, u] : uses) {
      if (u.first != 1 || (onSurfaceBoundary && onSurfaceBoundary(e.first, e.second))) continue;
      segments.push_back({positions[i][u.second[0]], positions[i][u.second[1]], i});
    }
  }
  const double cell = scale / 64;
  auto key = [&](const Vec3& p) {
    return std::array<int64_t, 3>{static_cast<int64_t>(std::floor(p[0] / cell)),
                                  static_cast<int64_t>(std::floor(p[1] / cell)),
                                  static_cast<int64_t>(std::floor(p[2] / cell))};
  };
  std::map<std::array<int64_t, 3>, std::vector<size_t>> grid;
  for (size_t s = 0; s < segments.size(); ++s) {
    const auto lo = key(min(segments[s].a, segments[s].b)), hi = key(max(segments[s].a, segments[s].b));
    for (int64_t x = lo[0]; x <= hi[0]; ++x)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t z = lo[2]; z <= hi[2]; ++z) grid[{x, y, z}].push_back(s);
  }
  auto distance = [](const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 d = b - a;
    const double t = std::clamp(dot(p - a, d) / std::max(dot(d, d), 1e-300), 0.0, 1.0);
    return (p - (a + t * d)).norm();
  };
  int64_t unmatched = 0;
  for (const Segment& s : segments) {
    const Vec3 mid = 0.5 * (s.a + s.b);
    bool found = false;
    for (size_t o : grid[key(mid)]) {
      const Segment& other = segments[o];
      if (other.tile == s.tile) continue;
      if (distance(mid, other.a, other.b) <= 1e-12 * scale &&
          distance(s.a, other.a, other.b) <= 1e-12 * scale &&
          distance(s.b, other.a, other.b) <= 1e-12 * scale) {
        found = true;
        break;
      }
      // The other way round: the other, finer edge lies on this one.
      if (distance(0.5 * (other.a + other.b), s.a, s.b) <= 1e-12 * scale &&
          distance(other.a, s.a, s.b) <= 1e-12 * scale && distance(other.b, s.a, s.b) <= 1e-12 * scale) {
        found = true;
        break;
      }
    }
    if (!found) ++unmatched;
  }
  return unmatched;
}

}  // namespace tessera::testing
