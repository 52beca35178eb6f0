#include "core/tessellation/region_merge.h"

#include <array>
#include <tuple>

#include <array>

namespace tessera {

SurfaceMesh mergeRegions(const std::map<uint64_t, RegionMesh>& regions) {
  SurfaceMesh out;
  // A vertex is its id and normal (creases split it per side); regions of
  // a display-only profile carry no ids, and there its position stands in:
  // border vertices decode bit-identically on both sides.
  using Key = std::tuple<uint64_t, std::array<double, 3>, std::array<double, 3>>;
  std::map<Key, int> index;
  for (const auto& [id, mesh] : regions) {
    const bool withIds = !mesh.vertexIds.empty();
    std::vector<int> map(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      const Vec3& n = mesh.normals[v];
      const Vec3& p = mesh.positions[v];
      const Key key{withIds ? mesh.vertexIds[v] : 0, {n[0], n[1], n[2]},
                    withIds ? std::array<double, 3>{} : std::array<double, 3>{p[0], p[1], p[2]}};
      auto [it, fresh] = index.emplace(key, static_cast<int>(out.positions.size()));
      if (fresh) out.positions.push_back(p), out.normals.push_back(n);
      map[v] = it->second;
    }
    for (const auto& t : mesh.triangles) out.triangles.push_back({map[t[0]], map[t[1]], map[t[2]]});
  }
  return out;
}

}  // namespace tessera
