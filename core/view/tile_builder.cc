#include "core/view/tile_builder.h"

#include "core/tessellation/displayed_vertices.h"
#include "core/tessellation/leaf_triangulation.h"

namespace tessera {

Expected<RegionMesh> buildTile(Document& doc, const TileTree& tree, const TileKey& tile) {
  if (!tree.contains(tile)) return notFound(tile.toString() + " is not a tile of this document");
  if (tile.level > doc.counts().maxLevel()) {
    return invalidArgument(tile.toString() + " is deeper than the document's level " +
                           std::to_string(doc.counts().maxLevel()));
  }
  return buildFacesAt(doc, tile.level, tree.facesShown(tile), tile.toString());
}

Expected<RegionMesh> buildFacesAt(Document& doc, int level, const std::vector<FaceId>& faces,
                                  const std::string& what) {
  doc.refineHierarchy(faces);
  // Growing for the limits' levels adds faces and vertices the gathering
  // may need: the triangles are gathered again until nothing more is
  // needed.
  for (int round = 0; round <= kMaxDocumentLevel + 1; ++round) {
    const SparseHierarchy& h = doc.hierarchy();
    std::vector<RefTriangle> triangles;
    std::vector<VertexRef> leaves;
    triangles.reserve(faces.size());
    for (const FaceId& f : faces) {
      const Index local = h.level(level).findFace(f.index());
      if (local == kNoIndex) return internalError(what + ": the hierarchy does not hold " + f.toString());
      triangulateFace(h, level, local, triangles);
      leaves.resize(triangles.size(), VertexRef{level, local});
    }
    std::vector<FaceId> growth;
    RegionMesh mesh = meshOfTriangles(h, doc.counts(), triangles, leaves, growth);
    if (growth.empty()) return mesh;
    doc.refineHierarchy(growth);
  }
  return internalError(what + ": the hierarchy does not hold the limits' rings after repeated growth");
}

}  // namespace tessera
