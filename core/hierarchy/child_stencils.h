// A vertex of a sparse level predicted from its parent level by the
// document's scheme: Loop's stencils (core/loop/interpolate.h) under a
// triangle split, Catmull-Clark's (core/catmark/stencils.h) under a quad
// split. Each reads only the parent, so a prediction is the uniform
// refinement's point whatever else the level holds (sparse_hierarchy.h).
#pragma once

#include <span>
#include <variant>

#include "core/catmark/stencils.h"
#include "core/hierarchy/ids.h"
#include "core/hierarchy/sparse_level.h"
#include "core/loop/interpolate.h"
#include "core/loop/loop_options.h"
#include "core/util/vec3.h"

namespace tessera {

class ChildStencils {
 public:
  ChildStencils(const SparseLevel& parent, const LoopOptions& options, SplitKind split);

  // The point of vertex v of `child`, the level split from the parent,
  // from the parent's points. Inline: the incremental update predicts
  // vertex after vertex, and a call per vertex cost Loop edits instructions
  // (docs/PERFORMANCE.md "Catmull-Clark in the hierarchy").
  Vec3 predict(const SparseLevel& child, Index v, std::span<const Vec3> parentPoints) {
    const Index o = child.origin[v];
    if (auto* loop = std::get_if<LoopStencils>(&stencils_)) {
      return child.isVertexChild(v) ? loop->vertexChild(o, parentPoints) : loop->edgeChild(o, parentPoints);
    }
    auto& catmark = std::get<CatmarkStencils>(stencils_);
    if (child.isVertexChild(v)) return catmark.vertexChild(o, parentPoints);
    if (child.isFaceChild(v)) return catmark.faceChild(o, parentPoints);
    return catmark.edgeChild(o, parentPoints);
  }

 private:
  std::variant<LoopStencils, CatmarkStencils> stencils_;
};

}  // namespace tessera
