#include "core/view/tile_tree.h"

#include <algorithm>
#include <string>

namespace tessera {

namespace {

constexpr int kClusterLevels = kTileDepth - 1;  // levels 0..4 are clusters

int clusterSize(int level) {
  return 1 << (2 * (kTileDepth - level));
}

}  // namespace

std::string TileKey::toString() const {
  if (isPreview()) return "the surface's preview";
  return "tile L" + std::to_string(level) + " " + FaceId::fromPacked(face).toString();
}

namespace {

constexpr uint64_t kClusterBit = uint64_t{1} << 63;
constexpr uint64_t kIndexMask = (uint64_t{1} << 58) - 1;
constexpr uint64_t kPreviewLevelBits = 31;  // never a cluster level (at most 4)

}  // namespace

uint64_t TileKey::regionId() const {
  if (level >= kTileDepth) return face;
  const uint64_t levelBits = isPreview() ? kPreviewLevelBits : static_cast<uint64_t>(level);
  return kClusterBit | (levelBits << 58) | FaceId::fromPacked(face).index();
}

TileKey TileKey::fromRegionId(uint64_t id) {
  if (id & kClusterBit) {
    const uint64_t levelBits = (id >> 58) & 31;
    return {levelBits == kPreviewLevelBits ? kPreviewLevel : static_cast<int>(levelBits),
            FaceId(0, id & kIndexMask).packed()};
  }
  return {FaceId::fromPacked(id).level() + kTileDepth, id};
}

template <typename Base>
TileTree TileTree::buildOver(const Base& base, const LevelCounts& counts, int maxLevel) {
  TileTree t;
  t.maxLevel_ = maxLevel;
  t.counts_ = counts;
  for (int l = 0; l <= std::min(kClusterLevels, maxLevel); ++l) {
    t.clusters_.push_back(l == 0 ? BaseFaceClusters::build(base, clusterSize(0))
                                 : BaseFaceClusters::buildWithin(base, clusterSize(l), t.clusters_.back()));
  }
  for (size_t l = 0; l + 1 < t.clusters_.size(); ++l) {
    const BaseFaceClusters& here = t.clusters_[l];
    const BaseFaceClusters& there = t.clusters_[l + 1];
    auto& seeds = t.childSeeds_.emplace_back(here.numClusters());
    for (uint32_t c = 0; c < static_cast<uint32_t>(here.numClusters()); ++c) {
      for (int f : here.facesOf(c)) {
        if (there.seedOf(there.clusterOf(f)) == f) seeds[c].push_back(f);
      }
    }
  }
  return t;
}

TileTree TileTree::build(const BaseTopology& base, const LevelCounts& counts, int maxLevel) {
  return buildOver(base, counts, maxLevel);
}

TileTree TileTree::build(const PolyTopology& base, const LevelCounts& counts, int maxLevel) {
  return buildOver(base, counts, maxLevel);
}

std::vector<TileKey> TileTree::roots() const {
  std::vector<TileKey> out;
  const BaseFaceClusters& c = clusters_.front();
  for (uint32_t k = 0; k < static_cast<uint32_t>(c.numClusters()); ++k)
    out.push_back({0, FaceId(0, static_cast<uint64_t>(c.seedOf(k))).packed()});
  return out;
}

std::vector<TileKey> TileTree::children(const TileKey& tile) const {
  std::vector<TileKey> out;
  if (tile.level >= maxLevel_) return out;
  const int next = tile.level + 1;
  if (next <= kClusterLevels) {
    // The clusters of the next level inside this one: those of its faces.
    const uint32_t mine =
        clusters_[tile.level].clusterOf(static_cast<int>(FaceId::fromPacked(tile.face).index()));
    for (int f : childSeeds_[tile.level][mine])
      out.push_back({next, FaceId(0, static_cast<uint64_t>(f)).packed()});
    return out;
  }
  for (const FaceId& f : rootFaces(tile)) {
    if (next == kTileDepth) {
      out.push_back({next, f.packed()});  // the cluster's faces, each a tile
    } else {
      const auto [first, last] = counts_.descendantsAt(f, f.level() + 1);
      for (uint64_t k = first; k < last; ++k) out.push_back({next, FaceId(f.level() + 1, k).packed()});
    }
  }
  return out;
}

TileKey TileTree::parent(const TileKey& tile) const {
  if (tile.level == 0) return tile;
  const FaceId f = FaceId::fromPacked(tile.face);
  // A cluster's (or, at level 5, a base face's) parent is the cluster of the
  // level above that holds its seed face; a deeper face's, its parent face.
  if (tile.level <= kTileDepth)
    return {tile.level - 1, clusterSeed(tile.level - 1, static_cast<int>(f.index()))};
  return {tile.level - 1, counts_.parentFace(f).packed()};
}

std::vector<FaceId> TileTree::rootFaces(const TileKey& tile) const {
  if (tile.level >= kTileDepth) return {FaceId::fromPacked(tile.face)};
  const BaseFaceClusters& c = clusters_[tile.level];
  std::vector<FaceId> out;
  for (int f : c.facesOf(c.clusterOf(static_cast<int>(FaceId::fromPacked(tile.face).index()))))
    out.push_back(FaceId(0, static_cast<uint64_t>(f)));
  return out;
}

std::vector<FaceId> TileTree::facesShown(const TileKey& tile) const {
  std::vector<FaceId> out;
  for (const FaceId& root : rootFaces(tile)) {
    const auto [first, last] = counts_.descendantsAt(root, tile.level);
    for (uint64_t k = first; k < last; ++k) out.push_back(FaceId(tile.level, k));
  }
  return out;
}

uint64_t TileTree::clusterSeed(int level, int face) const {
  const BaseFaceClusters& c = clusters_[level];
  return FaceId(0, static_cast<uint64_t>(c.seedOf(c.clusterOf(face)))).packed();
}

bool TileTree::contains(const TileKey& tile) const {
  if (tile.level < 0 || tile.level > maxLevel_) return false;
  const FaceId f = FaceId::fromPacked(tile.face);
  if (tile.level >= kTileDepth)
    return f.level() == tile.level - kTileDepth && f.index() < counts_.faces(f.level());
  if (f.level() != 0 || f.index() >= counts_.faces(0)) return false;
  const BaseFaceClusters& c = clusters_[tile.level];
  return c.seedOf(c.clusterOf(static_cast<int>(f.index()))) == static_cast<int>(f.index());
}

}  // namespace tessera
