#include "server/document/tile_cache.h"

#include <chrono>

#include "core/view/tile_preview.h"

namespace tessera::server {

TileCache::TileCache(Document& doc, const QuantizationGrid& grid, uint64_t maxBytes, ServerStats& stats)
    : doc_(doc),
      grid_(grid),
      maxBytes_(maxBytes),
      stats_(stats),
      hasPreview_(previewPays(static_cast<int64_t>(doc.counts().faces(0)))) {}

TileCache::~TileCache() {
  stats_.tileCacheBytes -= static_cast<int64_t>(bytes_);
}

TileCatalogue& TileCache::catalogue() {
  if (!catalogue_) catalogue_.emplace(doc_);
  return *catalogue_;
}

void TileCache::countBuilt() {
  if (!catalogue_) return;
  const int64_t built = catalogue_->built() + catalogue_->rebuilt();
  stats_.tilesBuilt += built - builtCounted_;
  builtCounted_ = built;
}

Expected<TileSelection> TileCache::select(const View& view, int64_t budget) {
  auto selection = selectTiles(view, catalogue(), budget);
  countBuilt();
  return selection;
}

Expected<std::vector<TileSelection>> TileCache::selectForEach(std::span<const View> views,
                                                              std::span<const int64_t> budgets,
                                                              int64_t newTiles,
                                                              const std::function<bool()>& stopBuilding) {
  auto selections = selectTilesForEach(views, catalogue(), budgets, newTiles, stopBuilding);
  countBuilt();
  return selections;
}

Expected<TileBounds> TileCache::bounds(const TileKey& key) {
  auto tile = catalogue().get(key);
  countBuilt();
  if (!tile.isOk()) return tile.status();
  return (*tile)->bounds;
}

Expected<EncodedTile> TileCache::encoded(const TileKey& key, uint64_t version) {
  auto found = entries_.find(key);
  if (found != entries_.end()) {
    byUse_.erase(found->second.lastUse);
    found->second.lastUse = ++useClock_;
    byUse_.emplace(found->second.lastUse, key);
    ++stats_.tileCacheHits;
    return found->second.tile;
  }
  const auto start = std::chrono::steady_clock::now();
  EncodedTile tile;
  if (key.isPreview()) {
    TESSERA_ASSIGN_OR_RETURN(SurfacePreview preview, surfacePreview(doc_));
    levelZeroTriangles_ = preview.levelZeroTriangles;
    TESSERA_ASSIGN_OR_RETURN(tile, encodeTile(doc_, key, preview.mesh, grid_, version));
  } else {
    TESSERA_ASSIGN_OR_RETURN(const RegionMesh* mesh, catalogue().mesh(key));
    TESSERA_ASSIGN_OR_RETURN(tile, encodeTile(doc_, key, *mesh, grid_, version));
    // The encoding is what is kept: the mesh goes, the bounds stay for
    // selecting (docs/VIEWS.md "The server").
    catalogue_->releaseMesh(key);
  }
  stats_.encodeLatency.addMicros(
      std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start)
          .count());
  countBuilt();
  ++stats_.tilesEncoded;
  const uint64_t size = tile.bytes->size();
  evictBeyond(maxBytes_ > size ? maxBytes_ - size : 0);
  entries_.emplace(key, Entry{tile, ++useClock_});
  byUse_.emplace(useClock_, key);
  bytes_ += size;
  stats_.tileCacheBytes += static_cast<int64_t>(size);
  return tile;
}

void TileCache::evictBeyond(uint64_t maxBytes) {
  while (bytes_ > maxBytes && !byUse_.empty()) {
    auto oldest = byUse_.begin();
    auto entry = entries_.find(oldest->second);
    const uint64_t size = entry->second.tile.bytes->size();
    bytes_ -= size;
    stats_.tileCacheBytes -= static_cast<int64_t>(size);
    ++stats_.tileCacheEvictions;
    entries_.erase(entry);
    byUse_.erase(oldest);
  }
}

void TileCache::forgetEncoding(const TileKey& key) {
  auto entry = entries_.find(key);
  if (entry == entries_.end()) return;
  const uint64_t size = entry->second.tile.bytes->size();
  bytes_ -= size;
  stats_.tileCacheBytes -= static_cast<int64_t>(size);
  byUse_.erase(entry->second.lastUse);
  entries_.erase(entry);
}

std::vector<TileKey> TileCache::invalidate(std::span<const VertexId> changedLimits) {
  // Before the tree exists only the preview can be held: any change may
  // reach a root, so it goes.
  if (!catalogue_) {
    if (!changedLimits.empty()) forgetEncoding(TileKey::preview());
    return {};
  }
  const std::vector<TileKey> gone =
      catalogue_->forget(TouchedTiles(doc_.hierarchy(), catalogue_->tree(), changedLimits));
  for (const TileKey& key : gone) {
    forgetEncoding(key);
    // The preview is made of every root: a root that changed changes it.
    if (key.level == 0) forgetEncoding(TileKey::preview());
  }
  return gone;
}

}  // namespace tessera::server
