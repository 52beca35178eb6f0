#include "client/view/control_cage.h"

#include <algorithm>
#include <numeric>
#include <string>

#include "core/hierarchy/ids.h"
#include "core/mesh/polygon_triangulation.h"
#include "core/util/vec3.h"

namespace tessera::view {

Expected<ControlCage> controlCageOf(const wire::Cage& reply) {
  ControlCage cage;
  cage.level = static_cast<int>(reply.level());
  cage.version = reply.version();
  if (reply.level() > 63) return parseError("cage: level " + std::to_string(reply.level()) + " has no ids");
  const int total = reply.vertices_size();
  struct Side {
    uint64_t a, b;
    int32_t face;
  };
  std::vector<Side> sides;
  int at = 0;
  for (int f = 0; f < reply.face_sizes_size(); ++f) {
    const uint32_t n = reply.face_sizes(f);
    if (n < 3)
      return parseError("cage: face " + std::to_string(f) + " has " + std::to_string(n) + " corners");
    if (n > static_cast<uint32_t>(total - at)) {
      return parseError("cage: face " + std::to_string(f) + " has " + std::to_string(n) +
                        " corners, but only " + std::to_string(total - at) + " of the " +
                        std::to_string(total) + " vertices are left");
    }
    ++cage.facesBySize[n];
    for (uint32_t k = 0; k < n; ++k) {
      const uint64_t index = reply.vertices(at + static_cast<int>(k));
      if (index > VertexId::kIndexMask)
        return parseError("cage: face " + std::to_string(f) + " has an index beyond 58 bits");
      cage.corners.push_back(VertexId(cage.level, index).packed());
    }
    for (uint32_t k = 0; k < n; ++k) {
      const uint64_t a = cage.corners[at + k], b = cage.corners[at + (k + 1) % n];
      sides.push_back({std::min(a, b), std::max(a, b), f});
    }
    at += static_cast<int>(n);
    cage.faceStarts.push_back(static_cast<uint32_t>(at));
  }
  if (at != total) {
    return parseError("cage: the faces use " + std::to_string(at) + " of the " + std::to_string(total) +
                      " vertices sent");
  }
  // An interior edge is a side of two faces: drawn once, knowing both.
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return std::tie(x.a, x.b, x.face) < std::tie(y.a, y.b, y.face);
  });
  for (const Side& s : sides) {
    if (!cage.edges.empty() && cage.edges.back() == std::make_pair(s.a, s.b)) {
      auto& faces = cage.edgeFaces.back();
      if (faces[1] < 0 && faces[0] != s.face) faces[1] = s.face;
      continue;
    }
    cage.edges.emplace_back(s.a, s.b);
    cage.edgeFaces.push_back({s.face, -1});
  }
  return cage;
}

std::vector<V3> cageSegments(const ControlCage& cage, const std::vector<ControlPoint>& points, V3 eye) {
  auto find = [&](uint64_t id) -> const ControlPoint* {
    auto it = std::lower_bound(points.begin(), points.end(), id,
                               [](const ControlPoint& p, uint64_t v) { return p.id < v; });
    return it != points.end() && it->id == id ? &*it : nullptr;
  };
  std::vector<uint8_t> front(cage.faces(), 0);
  std::vector<Vec3> corners;
  std::vector<int> order;
  for (size_t f = 0; f < cage.faces(); ++f) {
    corners.clear();
    for (uint32_t c = cage.faceStarts[f]; c < cage.faceStarts[f + 1]; ++c)
      if (const ControlPoint* p = find(cage.corners[c]))
        corners.emplace_back(p->position.x, p->position.y, p->position.z);
    if (corners.size() < 3) continue;
    order.resize(corners.size());
    std::iota(order.begin(), order.end(), 0);
    Vec3 centre(0, 0, 0);
    for (const Vec3& p : corners) centre += p;
    centre = centre * (1.0 / static_cast<double>(corners.size()));
    const Vec3 toEye = Vec3(eye.x, eye.y, eye.z) - centre;
    front[f] = (polygonNormal(corners, order) | toEye) > 0;
  }
  std::vector<V3> out;
  for (size_t i = 0; i < cage.edges.size(); ++i) {
    const auto [f0, f1] = cage.edgeFaces[i];
    if (!front[f0] && !(f1 >= 0 && front[f1])) continue;
    const ControlPoint* pa = find(cage.edges[i].first);
    const ControlPoint* pb = find(cage.edges[i].second);
    if (!pa || !pb) continue;
    out.push_back(pa->position);
    out.push_back(pb->position);
  }
  return out;
}

}  // namespace tessera::view
