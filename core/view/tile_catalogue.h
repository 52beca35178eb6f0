// The tiles of one document built on demand and kept: each (tile, document
// version) is tessellated and measured at most once, whoever asks
// (docs/VIEWS.md). A view's selection (tile_selection.h) reads
// bounds from it; a server encodes its meshes once for every viewer.
#pragma once

#include <map>
#include <memory>
#include <span>

#include "core/document/document.h"
#include "core/tessellation/region_codec.h"
#include "core/util/status.h"
#include "core/view/tile_error.h"
#include "core/view/tile_tree.h"

namespace tessera {

struct Tile {
  RegionMesh mesh;
  TileBounds bounds;
};

class TileCatalogue {
 public:
  explicit TileCatalogue(Document& doc)
      : doc_(doc), tree_(TileTree::build(doc.baseTopology(), doc.counts(), doc.counts().maxLevel())) {}

  const TileTree& tree() const { return tree_; }
  // The tile, built (and measured) the first time it is asked for.
  Expected<const Tile*> get(const TileKey& key);
  // Grows the hierarchy once for all these tiles (those not built yet), so
  // that building them one by one grows it no more: each growth rebuilds
  // the levels below it, and a selection asks for hundreds of tiles.
  void prepare(std::span<const TileKey> keys);
  // Tiles built so far (a statistic; each counts once).
  int64_t built() const { return built_; }
  // Forgets every tile (the document changed; a server forgets only those an edit reached).
  void clear() { tiles_.clear(); }

 private:
  Document& doc_;
  TileTree tree_;
  std::map<TileKey, std::unique_ptr<Tile>> tiles_;
  int64_t built_ = 0;
};

}  // namespace tessera
