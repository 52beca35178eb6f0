// Direct manipulation (seed 000 §2.2): the user drags a vertex's *limit*
// position; the control point that puts the limit there follows from the
// limit mask, an affine combination  L(v) = w_v p_v + sum_i w_i p_i,  solved
// for p_v with the neighbours fixed:  p_v' = p_v + (target - L(v)) / w_v.
// Only v's control point changes, so the limit surface moves at v and its
// same-level neighbours and nowhere else.
#pragma once

#include <span>

#include "core/loop/level.h"
#include "core/util/vec3.h"

namespace tessera {

// Weight of the vertex itself in its limit mask at this level: 1 - n w(n)
// for smooth and dart vertices, 2/3 on a crease, 1 at a corner. Always > 0.
double selfLimitWeight(const Level& level, Index v);

// The control point for v whose limit position is `target`.
Vec3 solveControlPoint(const Level& level, Index v, std::span<const Vec3> points, const Vec3& target);

}  // namespace tessera
