// Direct manipulation (Pulli & Lounsbery, "Hierarchical Editing and Rendering
// of Subdivision Surfaces" §2.2): the user drags a vertex's *limit*
// position; the control point that puts the limit there follows from the
// limit mask, an affine combination  L(v) = w_v p_v + sum_i w_i p_i,  solved
// for p_v with the neighbours fixed:  p_v' = p_v + (target - L(v)) / w_v.
// Only v's control point changes, so the limit surface moves at v and its
// same-level neighbours and nowhere else.
#pragma once

#include <span>

#include "core/loop/loop_options.h"
#include "core/topology/level.h"
#include "core/util/vec3.h"

namespace tessera {
class FarRingSharpness;  // local_ring.h
}

namespace tessera {

// Weight of the vertex itself in its exact limit mask at this level (limit.h):
// 1 - n w(n) for a smooth vertex, 2/3 on an infinitely sharp crease, 1 at a
// corner, the dart's eigenvector weight at a dart, and through the decay
// of a semi-sharp feature otherwise. Always > 0.
// `far` as for exactVertexLimit (exact_limit.h).
double selfLimitWeight(const Level& level, Index v, CreaseMethod method,
                       const FarRingSharpness* far = nullptr);

// The control point for v whose limit position is `target`.
Vec3 solveControlPoint(const Level& level, Index v, std::span<const Vec3> points, const Vec3& target,
                       CreaseMethod method, const FarRingSharpness* far = nullptr);

}  // namespace tessera
