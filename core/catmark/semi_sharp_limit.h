// Catmull-Clark limits where a semi-sharp feature has not decayed: a vertex
// whose own sharpness, or one of whose edges' sharpness, lies strictly
// between smooth and infinite. Limit()'s masks count such a feature as
// sharp, and so are not the surface's until the level is deeper than the
// sharpness (docs/LIMITS.md "Catmull-Clark limits").
//
// A vertex's one ring (the vertex, its edge neighbours and its faces'
// other corners) is closed under a step of Sdc's rules but for one
// reading: the vertex's child, the children of its edges and of its faces
// are the next level's ring, and they read the ring's points and the
// sharpness of the vertex and of its edges (the blending of Pulli &
// Lounsbery, "Hierarchical Editing and Rendering of Subdivision Surfaces"
// §2.4), except that Chaikin's decay of a semi-sharp edge's far half reads
// the far vertex's edges, and the rule of the edge's child vertex, which
// weighs its point, reads both halves. So the ring alone is refined
// (core/catmark/quad_split.h, interpolate.h: the dense refinement that
// equals OpenSubdiv Far's), a step at a time, with each far half decayed
// from the far vertex's edges as a whole level would (the level's own, or
// a sparse level's from its parent: core/hierarchy/sparse_far_rings.h),
// until no feature at the vertex is semi-sharp; the limit masks are taken
// there, where they are exact. After a step the far vertex of a ring edge
// is the vertex on it, whose edges are the edge's two halves and smooth
// ones inside faces, so the next step knows them.
//
// The result is linear in the ring's points, so it is kept, per thread, as
// weights over them for each configuration of the ring (its faces, the
// sharpness of the vertex and its edges, and under Chaikin's decay the far
// ends' edges): a vertex then costs a lookup and three dot products. The
// counterpart of Loop's decay matrices (core/loop/decay_matrix.h), under
// both decays.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "core/catmark/limit.h"
#include "core/catmark/polygon_level.h"
#include "core/loop/limit.h"
#include "core/loop/local_ring.h"
#include "core/topology/level.h"
#include "core/util/vec3.h"

namespace tessera {

// Whether vertex v's sharpness or one of its edges' is semi-sharp.
bool hasUndecayedSemiSharpness(const Level& level, Index v);

// Whether decayedLimitFrame takes v: a semi-sharp feature at it.
bool takesDecayedLimit(const Level& level, Index v, const CreaseOptions& options);

// The limit frame of vertex v (a complete vertex of an all-quad level) on
// the surface: its ring refined until its features decayed, then
// catmarkLimitFrame there. `far` gives the edges at a neighbour that the
// level does not hold whole (null: the level's own rings). Nothing if the
// ring cannot be rebuilt: the caller keeps Limit()'s masks.
std::optional<CatmarkLimitFrame> decayedLimitFrame(const Level& level, Index v, std::span<const Vec3> points,
                                                   const CreaseOptions& options,
                                                   const FarRingSharpness* far = nullptr);

// The weight of v's own control point in that limit position (which is
// affine in it): the frame of unit points, v's 1 and every other 0. For
// direct manipulation (catmarkSelfLimitWeight). Nothing as above.
std::optional<double> decayedSelfLimitWeight(const Level& level, Index v, const CreaseOptions& options,
                                             const FarRingSharpness* far = nullptr);

// The sides of v once its features decayed. Sharp edges bound a
// vertex's sides, and a semi-sharp edge is no bound once it decayed: v's
// sides are the decayed ring's (only its infinitely sharp edges and the
// boundary bound them), numbered as limitSideOfRingFace numbers that
// ring's, so side 0 is decayedLimitFrame's. The side of ring face
// `ringFace` (its position in v's ring at this level); nothing as above.
std::optional<int> decayedSideOfRingFace(const Level& level, Index v, int ringFace,
                                         const CreaseOptions& options, const FarRingSharpness* far = nullptr);

// Those sides other than side 0, each with its limit normal
// (catmarkOtherLimitSectors of the decayed ring) and its faces as
// positions of v's ring at this level. Nothing as above.
std::optional<std::vector<LimitSector>> decayedOtherLimitSectors(const Level& level, Index v,
                                                                 std::span<const Vec3> points,
                                                                 const CreaseOptions& options,
                                                                 const FarRingSharpness* far = nullptr);

}  // namespace tessera
