// Limit positions and tangents of the complete vertices of one sparse level
// by the document's scheme: Loop's eigenanalysis (core/loop/limit.h, with
// the far rings Chaikin's decay reads, sparse_far_rings.h) under a triangle
// split, Catmull-Clark's limit masks (core/catmark/limit.h, with the same
// far rings) under a quad split. Catmull-Clark's masks read each ring face's opposite corner from
// a level of quads: a base level with other polygons has no limits (its
// vertices have theirs one level down, after the first split).
#pragma once

#include <memory>
#include <optional>
#include <span>

#include "core/catmark/limit.h"
#include "core/hierarchy/ids.h"
#include "core/hierarchy/sparse_far_rings.h"
#include "core/hierarchy/sparse_level.h"
#include "core/loop/limit.h"
#include "core/loop/loop_options.h"
#include "core/util/vec3.h"

namespace tessera {

class LevelLimits {
 public:
  // `parent` is the level `level` was split from (null at level 0).
  // `scope` says whether the limits of the whole level are asked for
  // (CatmarkLimitEvaluator::Scope: a pass over the level first).
  LevelLimits(const SparseLevel& level, const SparseLevel* parent, const LoopOptions& options,
              SplitKind split,
              CatmarkLimitEvaluator::Scope scope = CatmarkLimitEvaluator::Scope::kSomeVertices);
  LevelLimits(const LevelLimits&) = delete;
  LevelLimits& operator=(const LevelLimits&) = delete;

  // Whether a level's complete vertices have limits under the split: every
  // level of Loop's, and of the quad split every all-quad level.
  static bool hasLimits(const Level& mesh, SplitKind split) {
    return split == SplitKind::kTriangles || mesh.allQuads();
  }
  // The limit frame of complete vertex v from the level's points; without
  // limits (a Catmull-Clark base of other polygons), the control point and
  // no tangents, so a zero normal. Inline, as ChildStencils::predict, for
  // the update's loops.
  LimitFrame frame(Index v, std::span<const Vec3> points) const {
    if (loop_) return loop_->frame(v, points);
    if (!catmark_) return {points[v], Vec3(0, 0, 0), Vec3(0, 0, 0)};
    const CatmarkLimitFrame f = catmark_->frame(v, points);
    return {f.position, f.tangent1, f.tangent2};
  }
  // What the hierarchy stores of complete vertex v's limit: its position
  // and unit normal (LimitFrame::normal), from frame().
  struct PositionNormal {
    Vec3 position;
    Vec3 normal;
  };
  PositionNormal positionAndNormal(Index v, std::span<const Vec3> points) const {
    const LimitFrame f = frame(v, points);
    return {f.position, f.normal()};
  }
  // The control point of complete vertex v whose limit position is
  // `target`, the others fixed (direct manipulation, Pulli & Lounsbery,
  // "Hierarchical Editing and Rendering of Subdivision Surfaces" §2.2):
  // Loop's exact limit (core/loop/direct_manipulation.h), or the
  // Catmull-Clark mask frame() takes (with a semi-sharp feature, the
  // decayed ring's: core/catmark/semi_sharp_limit.h).
  Vec3 solveControlPoint(Index v, std::span<const Vec3> points, const Vec3& target) const;

 private:
  const SparseLevel& level_;
  LoopOptions options_;
  SparseFarRings far_;
  std::optional<LimitEvaluator> loop_;            // under a triangle split
  std::optional<CatmarkLimitEvaluator> catmark_;  // under a quad split
};

}  // namespace tessera
