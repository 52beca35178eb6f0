// The far rings Chaikin's decay reads, on a sparse level (local_ring.h,
// FarRingSharpness). The limit of a complete vertex with a semi-sharp ring
// edge reads, under Chaikin's decay, the sharpness of every edge at that
// edge's far end; the level may not hold them all, since its padding
// completes the rings the Loop stencils read and no more (sparse_level.h).
// They follow from the parent level, whose vertices around a refined face
// are complete: a vertex's child has the halves of its parent's edges (a
// missing half inherits its parent edge's sharpness at that end, and no
// missing edge carries a tag, since a tag's edit node holds its edge); a
// vertex on a parent edge has the edge's two halves and interior edges of
// the parent's faces, and a vertex in a parent face (quads) interior edges
// only, smooth unless a tag is on them, and then present. Catmull-Clark's
// semi-sharp limits read them the same way (core/catmark/semi_sharp_limit.h).
#pragma once

#include <vector>

#include "core/hierarchy/sparse_level.h"
#include "core/loop/local_ring.h"
#include "core/loop/loop_options.h"

namespace tessera {

class SparseFarRings final : public FarRingSharpness {
 public:
  // `parent` is null at level 0, where every vertex is complete.
  SparseFarRings(const SparseLevel& level, const SparseLevel* parent, const LoopOptions& options)
      : level_(level), parent_(parent), options_(options) {}
  void edgesAt(Index u, std::vector<float>& out) const override;

 private:
  const SparseLevel& level_;
  const SparseLevel* parent_;
  const LoopOptions& options_;
};

}  // namespace tessera
