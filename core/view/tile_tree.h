// The tiles of a view-dependent subscription (docs/VIEWS.md): the
// surface cut into pieces that are each shown uniformly at one level, in a
// tree where a tile's children cover exactly its surface one level finer --
// the hierarchy of tiles that 3D Tiles streams by screen-space error, here
// made of the subdivision levels themselves.
//
//   level L <= 4: a cluster of up to 4^(5 - L) edge-connected base faces
//                 (1,024 at level 0, 4 at level 4), each cluster grown
//                 inside one cluster of level L - 1 (base_face_clusters.h),
//                 so clusters nest;
//   level L >= 5: one face of level L - 5 (a base face at level 5).
//
// Either way a full tile shows 4^5 = 1,024 triangles, and has about four
// children: the clusters of level L + 1 inside it, or, from level 4 on, its
// faces' children. A tile is named by its level and a packed FaceId: the
// cluster's lowest base face, or its face. The tree is a function of the base
// topology alone, like the region groups.
#pragma once

#include <compare>
#include <cstdint>
#include <span>
#include <vector>

#include "core/catmark/polygon_level.h"
#include "core/hierarchy/ids.h"
#include "core/tessellation/base_face_clusters.h"

namespace tessera {

inline constexpr int kTileDepth = 5;  // a full tile: 4^5 triangles
// The surface's preview (tile_preview.h) has this level: not a tile of the
// tree, never selected, only the first picture's placeholder.
inline constexpr int kPreviewLevel = -1;

struct TileKey {
  int level = 0;
  uint64_t face = 0;  // packed FaceId: the seed base face (level <= 4) or the face of level - 5

  friend auto operator<=>(const TileKey&, const TileKey&) = default;
  std::string toString() const;
  // The tile's region id on the wire (docs/PROTOCOL.md "Views"): for a
  // one-face tile (level >= 5), its face's packed id, as a profile's region
  // is named by its root face (and a lattice frame names it); for a cluster,
  // bit 63 set, the level in bits 58..62 and the seed base face below.
  uint64_t regionId() const;
  static TileKey fromRegionId(uint64_t id);
  // The surface's preview, and whether a key is it: its region id is the
  // cluster form with level bits 31 and index 0.
  static TileKey preview() { return {kPreviewLevel, 0}; }
  bool isPreview() const { return level == kPreviewLevel; }
};

class TileTree {
 public:
  // Tiles of levels 0..maxLevel over `base`: triangles of Loop's split, or
  // polygons of the quad split (a face's children and descendants follow
  // `counts`, docs/ARCHITECTURE.md "The quad split").
  static TileTree build(const BaseTopology& base, const LevelCounts& counts, int maxLevel);
  static TileTree build(const PolyTopology& base, const LevelCounts& counts, int maxLevel);

  int maxLevel() const { return maxLevel_; }
  std::vector<TileKey> roots() const;
  // Empty at maxLevel.
  std::vector<TileKey> children(const TileKey& tile) const;
  // Whether children(tile) is not empty: every tile above maxLevel has some.
  bool hasChildren(const TileKey& tile) const { return tile.level < maxLevel_; }
  // The tile one level coarser that covers this one; a root's is itself.
  TileKey parent(const TileKey& tile) const;
  // The faces the tile covers: base faces (level <= 5) or its one face.
  std::vector<FaceId> rootFaces(const TileKey& tile) const;
  // The faces of the tile's level it shows, in order.
  std::vector<FaceId> facesShown(const TileKey& tile) const;
  // Whether `tile` names a tile of this tree.
  bool contains(const TileKey& tile) const;
  // The packed FaceId naming the cluster of `level` (at most 4) that holds
  // base face `face`.
  uint64_t clusterSeed(int level, int face) const;

 private:
  template <typename Base>
  static TileTree buildOver(const Base& base, const LevelCounts& counts, int maxLevel);

  int maxLevel_ = 0;
  LevelCounts counts_{0, 0, 0, 0};
  std::vector<BaseFaceClusters> clusters_;  // levels 0..min(4, maxLevel)
  // Per cluster level below the deepest, per cluster: its children's seed
  // faces (a selection asks for them at every step of every view).
  std::vector<std::vector<std::vector<int>>> childSeeds_;
};

}  // namespace tessera
