#include "core/view/tile_catalogue.h"

#include <algorithm>

#include "core/view/tile_builder.h"

namespace tessera {

void TileCatalogue::prepare(std::span<const TileKey> keys) {
  std::vector<FaceId> faces;
  for (const TileKey& key : keys) {
    if (tiles_.count(key) || !tree_.contains(key)) continue;
    // tileBounds reads the next level from this one where it can (and
    // grows the hierarchy itself where it cannot: near edits).
    const auto shown = tree_.facesShown(key);
    faces.insert(faces.end(), shown.begin(), shown.end());
  }
  if (!faces.empty()) doc_.refineHierarchy(faces);
}

Expected<const Tile*> TileCatalogue::get(const TileKey& key) {
  // A tile not built yet is built by mesh(), as for a server's re-send,
  // then measured.
  if (!tiles_.count(key)) TESSERA_RETURN_IF_ERROR(mesh(key).status());
  Tile& tile = *tiles_.at(key);
  if (!tile.measured) TESSERA_RETURN_IF_ERROR(measure(key, tile));
  return &tile;
}

Status TileCatalogue::measure(const TileKey& key, Tile& tile) {
  // The deepest level's error follows from its parent's (tile_error.h).
  double parentError = 0;
  if (key.level >= doc_.counts().maxLevel() && key.level > 0) {
    TESSERA_ASSIGN_OR_RETURN(const Tile* p, get(tree_.parent(key)));
    parentError = p->bounds.error;
  }
  if (tile.meshReleased) {
    TESSERA_ASSIGN_OR_RETURN(tile.mesh, buildTile(doc_, tree_, key));
    tile.meshReleased = false;
    ++rebuilt_;
  }
  TESSERA_ASSIGN_OR_RETURN(tile.bounds, tileBounds(doc_, tree_, key, tile.mesh, parentError));
  tile.measured = true;
  if (tile.releaseWhenMeasured) {
    tile.releaseWhenMeasured = false;
    tile.mesh = RegionMesh{};
    tile.meshReleased = true;
  }
  return Status::ok();
}

Expected<const RegionMesh*> TileCatalogue::mesh(const TileKey& key) {
  auto found = tiles_.find(key);
  if (found == tiles_.end()) {
    TESSERA_ASSIGN_OR_RETURN(RegionMesh mesh, buildTile(doc_, tree_, key));
    const auto triangles = static_cast<int64_t>(mesh.triangles.size());
    found = tiles_.emplace(key, std::make_unique<Tile>(Tile{std::move(mesh), {}, triangles})).first;
    ++built_;
  }
  Tile& tile = *found->second;
  if (!tile.meshReleased) return &tile.mesh;
  TESSERA_ASSIGN_OR_RETURN(tile.mesh, buildTile(doc_, tree_, key));
  tile.meshReleased = false;
  ++rebuilt_;
  return &tile.mesh;
}

void TileCatalogue::releaseMesh(const TileKey& key) {
  auto found = tiles_.find(key);
  if (found == tiles_.end() || found->second->meshReleased) return;
  // Its bounds are measured from its mesh: kept until then.
  if (!found->second->measured) {
    found->second->releaseWhenMeasured = true;
    return;
  }
  found->second->mesh = RegionMesh{};
  found->second->meshReleased = true;
}

std::vector<TileKey> TileCatalogue::forget(const TouchedTiles& touched) {
  std::vector<TileKey> gone;
  if (touched.empty()) return gone;
  const int deepest = doc_.counts().maxLevel();
  // Key order is level first: a parent is judged before its children.
  for (auto it = tiles_.begin(); it != tiles_.end();) {
    const TileKey& key = it->first;
    const bool parentGone = key.level == deepest && key.level > 0 &&
                            std::binary_search(gone.begin(), gone.end(), tree_.parent(key));
    if (touched.touches(key) || parentGone) {
      gone.push_back(key);
      it = tiles_.erase(it);
    } else {
      ++it;
    }
  }
  return gone;
}

}  // namespace tessera
