#include "core/view/tile_preview.h"

#include <meshoptimizer.h>

#include <bit>
#include <limits>
#include <map>
#include <tuple>

#include "core/view/tile_builder.h"

namespace tessera {

namespace {

// A vertex of the joined surface: one id, one normal (a crease's sides are
// copies with their own normals, and stay copies: seams to meshoptimizer,
// which collapses them only along themselves).
using VertexKey = std::tuple<uint64_t, uint64_t, uint64_t, uint64_t>;

VertexKey keyOf(const RegionMesh& m, size_t v) {
  const Vec3& n = m.normals[v];
  return {m.vertexIds[v], std::bit_cast<uint64_t>(n[0]), std::bit_cast<uint64_t>(n[1]),
          std::bit_cast<uint64_t>(n[2])};
}

}  // namespace

Expected<RegionMesh> surfacePreview(const std::vector<const RegionMesh*>& roots) {
  RegionMesh joined;
  std::map<VertexKey, int> index;
  for (const RegionMesh* root : roots) {
    std::vector<int> to(root->positions.size());
    for (size_t v = 0; v < root->positions.size(); ++v) {
      auto [it, added] = index.try_emplace(keyOf(*root, v), static_cast<int>(joined.positions.size()));
      if (added) {
        joined.positions.push_back(root->positions[v]);
        joined.normals.push_back(root->normals[v]);
        joined.vertexIds.push_back(root->vertexIds[v]);
      }
      to[v] = it->second;
    }
    for (const auto& t : root->triangles) joined.triangles.push_back({to[t[0]], to[t[1]], to[t[2]]});
    if (joined.positions.size() >= std::numeric_limits<uint32_t>::max() / 4)
      return invalidArgument("preview: more than 2^30 vertices at level 0");
  }
  if (joined.triangles.size() <= kPreviewTriangles) return joined;

  std::vector<float> positions;
  positions.reserve(3 * joined.positions.size());
  for (const Vec3& p : joined.positions)
    for (int k = 0; k < 3; ++k) positions.push_back(static_cast<float>(p[k]));
  std::vector<uint32_t> indices;
  indices.reserve(3 * joined.triangles.size());
  for (const auto& t : joined.triangles)
    for (int k = 0; k < 3; ++k) indices.push_back(static_cast<uint32_t>(t[k]));
  // No error limit (1 is the mesh's whole extent): the count decides.
  std::vector<uint32_t> kept(indices.size());
  kept.resize(meshopt_simplify(kept.data(), indices.data(), indices.size(), positions.data(),
                               joined.positions.size(), sizeof(float) * 3, 3 * kPreviewTriangles, 1.0f));
  // Where topology stops the collapses short of the count (many seams or
  // non-manifold vertices), collapse by a coarser grid instead
  // (meshopt_simplifySloppy), which always reaches it.
  if (kept.size() > 2 * 3 * kPreviewTriangles) {
    kept.resize(indices.size());
    kept.resize(meshopt_simplifySloppy(kept.data(), indices.data(), indices.size(), positions.data(),
                                       joined.positions.size(), sizeof(float) * 3, 3 * kPreviewTriangles,
                                       1.0f));
  }
  // The vertices the kept triangles use, in their first use's order.
  RegionMesh out;
  std::vector<int> renumbered(joined.positions.size(), -1);
  for (size_t i = 0; i < kept.size(); i += 3) {
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k) {
      int& v = renumbered[kept[i + k]];
      if (v < 0) {
        v = static_cast<int>(out.positions.size());
        out.positions.push_back(joined.positions[kept[i + k]]);
        out.normals.push_back(joined.normals[kept[i + k]]);
        out.vertexIds.push_back(joined.vertexIds[kept[i + k]]);
      }
      t[k] = v;
    }
    out.triangles.push_back(t);
  }
  return out;
}

Expected<SurfacePreview> surfacePreview(Document& doc) {
  std::vector<FaceId> faces;
  faces.reserve(doc.counts().faces(0));
  for (uint64_t f = 0; f < doc.counts().faces(0); ++f) faces.emplace_back(0, f);
  TESSERA_ASSIGN_OR_RETURN(RegionMesh levelZero, buildFacesAt(doc, 0, faces, "the surface's preview"));
  SurfacePreview out;
  out.levelZeroTriangles = static_cast<int64_t>(levelZero.triangles.size());
  TESSERA_ASSIGN_OR_RETURN(out.mesh, surfacePreview({&levelZero}));
  return out;
}

}  // namespace tessera
