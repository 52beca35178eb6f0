#include "client/view/control_points.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/hierarchy/ids.h"

namespace tessera::view {

namespace {

V3 toV3(const Vec3& v) {
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

}  // namespace

std::vector<ControlPoint> controlPoints(const RegionMap& regions, int level) {
  std::map<uint64_t, ControlPoint> byId;
  for (const auto& [regionId, mesh] : regions) {
    for (size_t v = 0; v < mesh->vertexIds.size(); ++v) {
      const VertexId born = VertexId::fromPacked(mesh->vertexIds[v]);
      if (born.level() > level) continue;
      const VertexId id(level, born.index());
      byId.emplace(id.packed(), ControlPoint{id.packed(), toV3(mesh->positions[v]), toV3(mesh->normals[v])});
    }
  }
  std::vector<ControlPoint> out;
  out.reserve(byId.size());
  for (auto& [id, p] : byId) out.push_back(p);
  return out;
}

std::optional<size_t> pickPoint(const std::vector<ControlPoint>& points, const OrbitCamera& camera, int width,
                                int height, float px, float py, float radiusPixels) {
  std::optional<size_t> best;
  float bestDistance = radiusPixels * radiusPixels;
  const V3 eye = camera.eye();
  for (size_t i = 0; i < points.size(); ++i) {
    if (dot(points[i].normal, eye - points[i].position) < 0) continue;  // on the far side
    auto s = camera.project(points[i].position, width, height);
    if (!s) continue;
    const float dx = (*s)[0] - px, dy = (*s)[1] - py, d = dx * dx + dy * dy;
    if (d <= bestDistance) bestDistance = d, best = i;
  }
  return best;
}

V3 dragTarget(const OrbitCamera& camera, V3 anchor, float px, float py, int width, int height) {
  const Ray ray = camera.rayThrough(px, py, width, height);
  const V3 n = normalize(camera.eye() - camera.target());
  const float denom = dot(ray.direction, n);
  if (std::abs(denom) < 1e-6f) return anchor;
  const float t = dot(anchor - ray.origin, n) / denom;
  return ray.origin + ray.direction * t;
}

std::vector<uint64_t> levelNeighbours(const RegionMap& regions, uint64_t vertex, int level) {
  // Displayed triangle edges among the vertices born at level + 1 or before,
  // by index (an index has one birth level).
  std::map<uint64_t, std::set<uint64_t>> joined;
  std::map<uint64_t, int> born;
  for (const auto& [regionId, mesh] : regions) {
    for (const auto& t : mesh->triangles) {
      for (int k = 0; k < 3; ++k) {
        const VertexId a = VertexId::fromPacked(mesh->vertexIds[t[k]]);
        const VertexId b = VertexId::fromPacked(mesh->vertexIds[t[(k + 1) % 3]]);
        if (a.level() > level + 1 || b.level() > level + 1) continue;
        joined[a.index()].insert(b.index());
        joined[b.index()].insert(a.index());
        born[a.index()] = a.level(), born[b.index()] = b.level();
      }
    }
  }
  const uint64_t v = VertexId::fromPacked(vertex).index();
  std::set<uint64_t> out;
  for (uint64_t n : joined[v]) {
    if (born[n] <= level) {
      out.insert(VertexId(level, n).packed());  // shown at `level`: a triangle edge is an edge
      continue;
    }
    // Shown at level + 1: n lies on an edge of `level`, whose other end is
    // its only other neighbour born by then.
    for (uint64_t far : joined[n])
      if (far != v && born[far] <= level) out.insert(VertexId(level, far).packed());
  }
  return {out.begin(), out.end()};
}

std::vector<V3> segmentPoints(V3 a, V3 b, int count) {
  std::vector<V3> out;
  for (int i = 0; i < count; ++i)
    out.push_back(a + (b - a) * (static_cast<float>(i) / static_cast<float>(count - 1)));
  return out;
}

bool bounds(const RegionMap& regions, V3* lo, V3* hi) {
  bool any = false;
  for (const auto& [id, mesh] : regions) {
    for (const Vec3& p : mesh->positions) {
      const V3 q = toV3(p);
      if (!any) *lo = *hi = q, any = true;
      lo->x = std::min(lo->x, q.x), lo->y = std::min(lo->y, q.y), lo->z = std::min(lo->z, q.z);
      hi->x = std::max(hi->x, q.x), hi->y = std::max(hi->y, q.y), hi->z = std::max(hi->z, q.z);
    }
  }
  return any;
}

float controlPointDiameter(V3 lo, V3 hi, size_t count) {
  const float diagonal = length(hi - lo);
  const float spacing = diagonal / std::sqrt(static_cast<float>(std::max<size_t>(count, 1)));
  return std::clamp(spacing / 3, diagonal * 0.0015f, diagonal * 0.015f);
}

}  // namespace tessera::view
