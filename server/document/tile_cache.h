// One document's tiles for its view-dependent subscribers (docs/VIEWS.md
// "The server"): each (tile, document state) tessellated and Draco-encoded
// at most once, whoever asks and whatever their cameras, and kept encoded
// up to a memory bound (--tile-cache-bytes; the least recently used go
// first, and come back built again). An edit forgets the tiles it reached
// (core/view/tile_invalidation.h); the others stay encoded.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "core/document/document.h"
#include "core/tessellation/quantization_grid.h"
#include "core/view/tile_catalogue.h"
#include "core/view/tile_encoding.h"
#include "core/view/tile_selection.h"
#include "server/base/server_stats.h"

namespace tessera::server {

class TileCache {
 public:
  TileCache(Document& doc, const QuantizationGrid& grid, uint64_t maxBytes, ServerStats& stats);
  ~TileCache();
  TileCache(const TileCache&) = delete;
  TileCache& operator=(const TileCache&) = delete;

  // The tile tree, built on first use: a new viewer's preview needs none,
  // and goes before it (docs/VIEWS.md "The first picture").
  const TileTree& tree() { return catalogue().tree(); }
  // The tiles `view` needs (tile_selection.h), in sending order.
  Expected<TileSelection> select(const View& view, int64_t budget);
  // The same for many views at once (selectTilesForEach): what a flush or a
  // round of camera moves asks for every subscriber; `newTiles` >= 0 and
  // `stopBuilding` bound the tiles the walk builds (its selections may then
  // be incomplete).
  Expected<std::vector<TileSelection>> selectForEach(std::span<const View> views,
                                                     std::span<const int64_t> budgets, int64_t newTiles = -1,
                                                     const std::function<bool()>& stopBuilding = {});
  // A tile's bounds at the document's state, built if an edit forgot them.
  Expected<TileBounds> bounds(const TileKey& key);
  // Whether bounds() has them without building.
  bool hasBounds(const TileKey& key) const { return catalogue_ && catalogue_->isBuilt(key); }
  // The tile encoded at the document's state: cached, or built (if its mesh
  // was released) and encoded once now; `version` goes into its header.
  // TileKey::preview() is the surface's preview (core/view/tile_preview.h),
  // made from the document without the tile tree, cached the same way and
  // forgotten with any root.
  Expected<EncodedTile> encoded(const TileKey& key, uint64_t version);
  // Whether a new viewer's first picture is the preview (previewPays).
  bool hasPreview() const { return hasPreview_; }
  // The triangles of the level-0 surface (every root together), known once
  // the preview was made: the most a view's coarsest tiles can hold.
  std::optional<int64_t> levelZeroTriangles() const { return levelZeroTriangles_; }
  // An edit changed these limits: the tiles it reached are forgotten,
  // encodings and bounds; returns them in key order.
  std::vector<TileKey> invalidate(std::span<const VertexId> changedLimits);
  uint64_t bytes() const { return bytes_; }

 private:
  void evictBeyond(uint64_t maxBytes);
  void countBuilt();
  // Forgets one encoding, if cached.
  void forgetEncoding(const TileKey& key);
  TileCatalogue& catalogue();

  Document& doc_;
  std::optional<TileCatalogue> catalogue_;
  const QuantizationGrid& grid_;
  const uint64_t maxBytes_;
  ServerStats& stats_;
  struct Entry {
    EncodedTile tile;
    uint64_t lastUse = 0;
  };
  std::map<TileKey, Entry> entries_;
  std::map<uint64_t, TileKey> byUse_;  // lastUse -> tile: the least recently used first
  uint64_t useClock_ = 0, bytes_ = 0;
  int64_t builtCounted_ = 0;
  bool hasPreview_ = false;
  std::optional<int64_t> levelZeroTriangles_;
};

}  // namespace tessera::server
