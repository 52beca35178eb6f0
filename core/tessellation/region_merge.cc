#include "core/tessellation/region_merge.h"

#include <array>
#include <numeric>
#include <tuple>
#include <vector>

namespace tessera {

namespace {

// Where a crease crosses a flat area its two sides' copies of a vertex have
// the same normal and merge by key, while their neighbours along the crease
// stay apart: the merged vertex's triangles form two fans that touch only
// at it (a bowtie, which mesh readers refuse). Each vertex is split into
// one copy per fan: triangles around it join across an edge to the same
// neighbour, in opposite directions as an oriented surface uses it.
void splitFans(SurfaceMesh& mesh) {
  const int numVertices = static_cast<int>(mesh.positions.size());
  std::vector<std::vector<std::pair<int, int>>> around(numVertices);  // (triangle, corner)
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    for (int k = 0; k < 3; ++k) around[mesh.triangles[t][k]].push_back({t, k});
  }
  for (int v = 0; v < numVertices; ++v) {
    const auto& corners = around[v];
    if (corners.size() < 2) continue;
    std::vector<int> parent(corners.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    // Corner i's next neighbour equal to corner j's previous one: the
    // triangles share the edge v-next.
    for (size_t i = 0; i < corners.size(); ++i) {
      const auto& ti = mesh.triangles[corners[i].first];
      const int next = ti[(corners[i].second + 1) % 3];
      for (size_t j = 0; j < corners.size(); ++j) {
        const auto& tj = mesh.triangles[corners[j].first];
        if (i != j && tj[(corners[j].second + 2) % 3] == next)
          parent[find(static_cast<int>(i))] = find(static_cast<int>(j));
      }
    }
    std::vector<int> copyOfPiece(corners.size(), -1);
    const int firstPiece = find(0);
    copyOfPiece[firstPiece] = v;
    for (size_t i = 0; i < corners.size(); ++i) {
      const int piece = find(static_cast<int>(i));
      if (copyOfPiece[piece] < 0) {
        copyOfPiece[piece] = static_cast<int>(mesh.positions.size());
        mesh.positions.push_back(mesh.positions[v]);
        mesh.normals.push_back(mesh.normals[v]);
      }
      mesh.triangles[corners[i].first][corners[i].second] = copyOfPiece[piece];
    }
  }
}

}  // namespace

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
      const Key key{withIds ? mesh.vertexIds[v] : 0,
                    {n[0], n[1], n[2]},
                    withIds ? std::array<double, 3>{} : std::array<double, 3>{p[0], p[1], p[2]}};
      auto [it, fresh] = index.emplace(key, static_cast<int>(out.positions.size()));
      if (fresh) out.positions.push_back(p), out.normals.push_back(n);
      map[v] = it->second;
    }
    for (const auto& t : mesh.triangles) out.triangles.push_back({map[t[0]], map[t[1]], map[t[2]]});
  }
  splitFans(out);
  return out;
}

}  // namespace tessera
