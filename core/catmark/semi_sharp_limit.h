// Catmull-Clark limits where a semi-sharp feature has not decayed: a vertex
// whose own sharpness, or one of whose edges' sharpness, lies strictly
// between smooth and infinite. Limit()'s masks count such a feature as
// sharp, and so are not the surface's until the level is deeper than the
// sharpness (docs/LIMITS.md "Catmull-Clark limits").
//
// A vertex's one ring (the vertex, its edge neighbours and its faces'
// other corners) is closed under a step of Sdc's rules: the vertex's child,
// the children of its edges and of its faces are the next level's ring, and
// they read the ring's points and the sharpness of the vertex and of its
// edges only (the blending of Pulli & Lounsbery, "Hierarchical Editing and
// Rendering of Subdivision Surfaces" §2.4, and Chaikin's decay read the
// same). So the ring alone is refined (core/catmark/quad_split.h,
// interpolate.h: the dense refinement that equals OpenSubdiv Far's), a step
// at a time, until no feature at the vertex is semi-sharp, and the limit
// masks are taken there, where they are exact. The counterpart of Loop's
// decay matrices (core/loop/decay_matrix.h).
//
// Under uniform decay only. Chaikin's decay of an edge at its far end reads
// the far vertex's other edges, and the rule of the edge's child vertex
// reads both halves, so the ring is not closed: there the masks still count
// a semi-sharp feature as sharp (docs/LIMITS.md).
#pragma once

#include <optional>
#include <span>

#include "core/catmark/limit.h"
#include "core/catmark/polygon_level.h"
#include "core/topology/level.h"
#include "core/util/vec3.h"

namespace tessera {

// Whether vertex v's sharpness or one of its edges' is semi-sharp.
bool hasUndecayedSemiSharpness(const Level& level, Index v);

// Whether decayedLimitFrame takes v: a semi-sharp feature under uniform decay.
bool takesDecayedLimit(const Level& level, Index v, const CreaseOptions& options);

// The limit frame of vertex v (a complete vertex of an all-quad level) on
// the surface: its ring refined until its features decayed, then
// catmarkLimitFrame there. Nothing under Chaikin's decay, or if the ring
// cannot be rebuilt: the caller keeps Limit()'s masks.
std::optional<CatmarkLimitFrame> decayedLimitFrame(const Level& level, Index v, std::span<const Vec3> points,
                                                   const CreaseOptions& options);

// The weight of v's own control point in that limit position (which is
// affine in it): the frame of unit points, v's 1 and every other 0. For
// direct manipulation (catmarkSelfLimitWeight). Nothing as above.
std::optional<double> decayedSelfLimitWeight(const Level& level, Index v, const CreaseOptions& options);

}  // namespace tessera
