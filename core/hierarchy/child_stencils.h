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
  // from the parent's points.
  Vec3 predict(const SparseLevel& child, Index v, std::span<const Vec3> parentPoints);

 private:
  std::variant<LoopStencils, CatmarkStencils> stencils_;
};

}  // namespace tessera
