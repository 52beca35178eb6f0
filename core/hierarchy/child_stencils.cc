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

Vec3 ChildStencils::predict(const SparseLevel& child, Index v, std::span<const Vec3> parentPoints) {
  const Index o = child.origin[v];
  if (auto* loop = std::get_if<LoopStencils>(&stencils_)) {
    return child.isVertexChild(v) ? loop->vertexChild(o, parentPoints) : loop->edgeChild(o, parentPoints);
  }
  auto& catmark = std::get<CatmarkStencils>(stencils_);
  if (child.isVertexChild(v)) return catmark.vertexChild(o, parentPoints);
  if (child.isFaceChild(v)) return catmark.faceChild(o, parentPoints);
  return catmark.edgeChild(o, parentPoints);
}

}  // namespace tessera
