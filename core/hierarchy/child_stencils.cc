#include "core/hierarchy/child_stencils.h"

namespace tessera {

namespace {

std::variant<LoopStencils, CatmarkStencils> stencilsFor(const Level& parent, const LoopOptions& options,
                                                        SplitKind split) {
  if (split == SplitKind::kQuads)
    return std::variant<LoopStencils, CatmarkStencils>(std::in_place_type<CatmarkStencils>, parent, options);
  return std::variant<LoopStencils, CatmarkStencils>(std::in_place_type<LoopStencils>, parent, options);
}

}  // namespace

ChildStencils::ChildStencils(const SparseLevel& parent, const LoopOptions& options, SplitKind split)
    : stencils_(stencilsFor(parent.mesh, options, split)) {}

}  // namespace tessera
