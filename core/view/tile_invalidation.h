// Which tiles an edit reached (docs/VIEWS.md "Edits and tiles"). A tile
// shows the limits of its level's vertices and reads, for its error, those
// of the next level under it; every triangle of any level that uses a
// vertex lies in that vertex's ring of faces at its own level, or under
// it. So the tiles an edit changed -- in mesh or in bounds -- are those
// over the rings of the vertices whose limits changed: a cluster tile
// holding a base face under a ring, a one-face tile whose face is in a
// ring, above one, or under one.
#pragma once

#include <set>
#include <span>

#include "core/hierarchy/ids.h"
#include "core/hierarchy/sparse_hierarchy.h"
#include "core/view/tile_tree.h"

namespace tessera {

class TouchedTiles {
 public:
  // `changedLimits`: vertices of the levels `h` holds (others are skipped:
  // no tile was built over them).
  TouchedTiles(const SparseHierarchy& h, const TileTree& tree, std::span<const VertexId> changedLimits);

  bool touches(const TileKey& tile) const;
  bool empty() const { return rings_.empty(); }

 private:
  std::set<uint64_t> rings_;      // packed FaceIds: the faces around each changed vertex
  std::set<uint64_t> ancestors_;  // packed FaceIds: those faces and every face above one
  std::set<TileKey> clusters_;    // cluster tiles holding a base face under a ring
  LevelCounts counts_;            // the split, for a face's ancestors
};

}  // namespace tessera
