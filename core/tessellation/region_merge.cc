#include "core/tessellation/region_merge.h"

#include <array>

namespace tessera {

SurfaceMesh mergeRegions(const std::map<uint64_t, RegionMesh>& regions) {
  SurfaceMesh out;
  std::map<std::pair<uint64_t, std::array<double, 3>>, int> index;
  for (const auto& [id, mesh] : regions) {
    std::vector<int> map(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      const Vec3& n = mesh.normals[v];
      auto [it, fresh] = index.emplace(std::make_pair(mesh.vertexIds[v], std::array<double, 3>{n[0], n[1], n[2]}),
                                       static_cast<int>(out.positions.size()));
      if (fresh) out.positions.push_back(mesh.positions[v]), out.normals.push_back(n);
      map[v] = it->second;
    }
    for (const auto& t : mesh.triangles) out.triangles.push_back({map[t[0]], map[t[1]], map[t[2]]});
  }
  return out;
}

}  // namespace tessera
