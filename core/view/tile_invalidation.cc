#include "core/view/tile_invalidation.h"

#include <algorithm>

namespace tessera {

TouchedTiles::TouchedTiles(const SparseHierarchy& h, const TileTree& tree,
                           std::span<const VertexId> changedLimits)
    : counts_(h.counts()) {
  for (VertexId id : changedLimits) {
    const int l = id.level();
    if (l >= h.numLevels()) continue;
    const auto& level = h.level(l);
    const Index v = level.findVertex(id.index());
    if (v == kNoIndex) continue;
    for (Index f : level.mesh.ringFacesOf(v)) {
      if (f < 0) continue;
      rings_.insert(FaceId(l, level.faceIds[f]).packed());
    }
  }
  std::set<int> baseFaces;
  for (uint64_t packed : rings_) {
    const FaceId f = FaceId::fromPacked(packed);
    for (int j = f.level(); j >= 0; --j) {
      if (!ancestors_.insert(counts_.ancestorAt(f, j).packed()).second) break;
    }
    baseFaces.insert(static_cast<int>(counts_.baseFace(f).index()));
  }
  for (int l = 0; l < kTileDepth && l <= tree.maxLevel(); ++l) {
    for (int b : baseFaces) clusters_.insert({l, tree.clusterSeed(l, b)});
  }
}

bool TouchedTiles::touches(const TileKey& tile) const {
  if (tile.level < kTileDepth) return clusters_.count(tile) > 0;
  // A ring face at or under the tile's face, or above it.
  const FaceId f = FaceId::fromPacked(tile.face);
  if (ancestors_.count(f.packed())) return true;
  for (int j = f.level() - 1; j >= 0; --j) {
    if (rings_.count(counts_.ancestorAt(f, j).packed())) return true;
  }
  return false;
}

}  // namespace tessera
