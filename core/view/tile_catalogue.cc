#include "core/view/tile_catalogue.h"

#include "core/view/tile_builder.h"

namespace tessera {

void TileCatalogue::prepare(std::span<const TileKey> keys) {
  std::vector<FaceId> faces;
  for (const TileKey& key : keys) {
    if (tiles_.count(key) || !tree_.contains(key)) continue;
    for (const FaceId& f : tree_.facesShown(key)) {
      faces.push_back(f);
      // tileBounds reads the next level under each face.
      if (key.level < doc_.counts().maxLevel()) faces.push_back(FaceId(f.level() + 1, 4 * f.index()));
    }
  }
  if (!faces.empty()) doc_.refineHierarchy(faces);
}

Expected<const Tile*> TileCatalogue::get(const TileKey& key) {
  auto found = tiles_.find(key);
  if (found != tiles_.end()) return found->second.get();
  // The deepest level's error follows from its parent's (tile_error.h).
  double parentError = 0;
  if (key.level >= doc_.counts().maxLevel() && key.level > 0) {
    TESSERA_ASSIGN_OR_RETURN(const Tile* p, get(tree_.parent(key)));
    parentError = p->bounds.error;
  }
  TESSERA_ASSIGN_OR_RETURN(RegionMesh mesh, buildTile(doc_, tree_, key));
  TESSERA_ASSIGN_OR_RETURN(TileBounds bounds, tileBounds(doc_, tree_, key, mesh, parentError));
  auto tile = std::make_unique<Tile>(Tile{std::move(mesh), bounds});
  const Tile* out = tile.get();
  tiles_.emplace(key, std::move(tile));
  ++built_;
  return out;
}

}  // namespace tessera
