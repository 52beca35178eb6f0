#include "core/hierarchy/level_limits.h"

#include "core/catmark/limit.h"
#include "core/loop/direct_manipulation.h"

namespace tessera {

LevelLimits::LevelLimits(const SparseLevel& level, const SparseLevel* parent, const LoopOptions& options,
                         SplitKind split, CatmarkLimitEvaluator::Scope scope)
    : level_(level), options_(options), far_(level, parent, options) {
  if (split == SplitKind::kTriangles) {
    loop_.emplace(level.mesh, options.creaseMethod, &far_);
  } else if (hasLimits(level.mesh, split)) {
    catmark_.emplace(level.mesh, options, &far_, scope);
  }
}

Vec3 LevelLimits::solveControlPoint(Index v, std::span<const Vec3> points, const Vec3& target) const {
  if (loop_) return tessera::solveControlPoint(level_.mesh, v, points, target, options_.creaseMethod, &far_);
  if (!catmark_) return target;  // no limit: the control point is what is shown
  const Vec3 limit = catmark_->frame(v, points).position;
  return points[v] + (1.0 / catmarkSelfLimitWeight(level_.mesh, v, options_, &far_)) * (target - limit);
}

}  // namespace tessera
