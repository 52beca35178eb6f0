// The tiles of one document built on demand and kept: each (tile, document
// version) is tessellated and measured at most once, whoever asks
// (docs/VIEWS.md). A view's selection (tile_selection.h) reads
// bounds from it; a server encodes its meshes once for every viewer.
#pragma once

#include <map>
#include <memory>
#include <span>
#include <variant>

#include "core/document/document.h"
#include "core/tessellation/region_codec.h"
#include "core/util/status.h"
#include "core/view/tile_error.h"
#include "core/view/tile_invalidation.h"
#include "core/view/tile_tree.h"

namespace tessera {

struct Tile {
  RegionMesh mesh;    // empty once released (releaseMesh)
  TileBounds bounds;  // once measured
  int64_t triangles = 0;
  bool meshReleased = false;
  // A tile built for its mesh alone (TileCatalogue::mesh) is measured when
  // its bounds are first asked for; its mesh stays until then, released
  // after if releaseMesh came meanwhile.
  bool measured = false, releaseWhenMeasured = false;
};

class TileCatalogue {
 public:
  explicit TileCatalogue(Document& doc)
      : doc_(doc),
        tree_(std::visit(
            [&](const auto& base) { return TileTree::build(base, doc.counts(), doc.counts().maxLevel()); },
            doc.base())) {}

  const TileTree& tree() const { return tree_; }
  const Document& document() const { return doc_; }
  // The tile, built and measured the first time it is asked for.
  Expected<const Tile*> get(const TileKey& key);
  // Whether get would find it built and measured (an edit forgets what it
  // reached).
  bool isBuilt(const TileKey& key) const {
    auto found = tiles_.find(key);
    return found != tiles_.end() && found->second->measured;
  }
  // Grows the hierarchy once for all these tiles (those not built yet), so
  // that building them one by one grows it no more: each growth rebuilds
  // the levels below it, and a selection asks for hundreds of tiles.
  void prepare(std::span<const TileKey> keys);
  // The tile's mesh, built again if it was released. A tile not built yet
  // is built without its bounds: a server re-sends the tiles an edit
  // reached before it measures them (docs/VIEWS.md "The server").
  Expected<const RegionMesh*> mesh(const TileKey& key);
  // Frees a tile's mesh and keeps its bounds (once measured): a server that
  // holds the tile's encoding needs only those to select (docs/VIEWS.md
  // "The tile cache").
  void releaseMesh(const TileKey& key);
  // Tiles built so far, and meshes built again after a release (statistics).
  int64_t built() const { return built_; }
  int64_t rebuilt() const { return rebuilt_; }
  size_t size() const { return tiles_.size(); }
  // Forgets every tile (the document changed).
  void clear() { tiles_.clear(); }
  // Forgets the tiles an edit reached (tile_invalidation.h), and the
  // deepest level's tiles whose parent goes (their error is the parent's
  // over 4); returns them, in key order.
  std::vector<TileKey> forget(const TouchedTiles& touched);

 private:
  // Measures `tile` (key's), built before without its bounds.
  Status measure(const TileKey& key, Tile& tile);

  Document& doc_;
  TileTree tree_;
  std::map<TileKey, std::unique_ptr<Tile>> tiles_;
  int64_t built_ = 0, rebuilt_ = 0;
};

}  // namespace tessera
