#include "core/view/tile_error.h"

#include <algorithm>

#include "core/tessellation/displayed_vertices.h"

namespace tessera {

namespace {

BoundingSphere sphereOf(const RegionMesh& mesh) {
  if (mesh.positions.empty()) return {};
  Vec3 lo = mesh.positions[0], hi = lo;
  for (const Vec3& p : mesh.positions)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  BoundingSphere s{0.5 * (lo + hi), 0};
  for (const Vec3& p : mesh.positions) s.radius = std::max(s.radius, (p - s.centre).norm());
  return s;
}

}  // namespace

Expected<TileBounds> tileBounds(Document& doc, const TileTree& tree, const TileKey& tile,
                                const RegionMesh& mesh, double parentError) {
  if (!tree.contains(tile)) return notFound(tile.toString() + " is not a tile of this document");
  TileBounds b;
  b.sphere = sphereOf(mesh);
  const int l = tile.level;
  if (l >= doc.counts().maxLevel()) {
    b.error = parentError / 4;
    b.sphere.radius += b.error;
    return b;
  }
  const std::vector<FaceId> faces = tree.facesShown(tile);
  // A face is refined once a face below it is demanded: one child each.
  std::vector<FaceId> children;
  children.reserve(faces.size());
  for (const FaceId& f : faces) children.push_back(FaceId(l + 1, 4 * f.index()));
  doc.refineHierarchy(children);
  for (int round = 0; round <= kMaxDocumentLevel + 1; ++round) {
    const SparseHierarchy& h = doc.hierarchy();
    const SparseLevel& level = h.level(l);
    std::vector<FaceId> growth;
    double worst = 0;
    auto limit = [&](int at, Index v) -> std::optional<Vec3> {
      const auto source = limitSource(h, doc.counts(), VertexRef{at, v}, growth);
      if (!source) return std::nullopt;
      return h.limitPosition(source->level, source->local);
    };
    for (const FaceId& f : faces) {
      const Index local = level.findFace(f.index());
      if (local == kNoIndex)
        return internalError(tile.toString() + ": the hierarchy does not hold " + f.toString());
      for (Index e : level.mesh.triangleEdges(local)) {
        const Index m = level.childOfEdge[e];
        if (m == kNoIndex) return internalError(tile.toString() + ": " + f.toString() + " is not refined");
        const auto a = limit(l, level.mesh.edgeVertices[e][0]), c = limit(l, level.mesh.edgeVertices[e][1]);
        const auto mid = limit(l + 1, m);
        if (!a || !c || !mid) continue;
        worst = std::max(worst, (*mid - 0.5 * (*a + *c)).norm());
      }
    }
    if (growth.empty()) {
      b.midpoints = worst;
      b.error = worst * 4.0 / 3.0;
      b.sphere.radius += b.error;
      return b;
    }
    doc.refineHierarchy(growth);
  }
  return internalError(tile.toString() +
                       ": the hierarchy does not hold the limits' rings after repeated growth");
}

}  // namespace tessera
