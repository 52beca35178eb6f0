// What an interpolating vertex (docs/INTERPOLATION.md, core/loop/ghost_ring.h)
// forbids around it, checked on the canonical ids alone (hierarchy/incidence.h).
//
// V0 of level l stays at its control point because, from level l+1 on, its
// descendant is the centroid of its ring and the plain smooth (or crease)
// rules keep it so (eq. 4-5 of the paper that ghost_ring.h cites). So below
// level l nothing may disturb that: no move of V0's descendants or of their
// ring neighbours (a detail offset there moves the centroid), and no
// sharpness on V0, its descendants or their edges at level l or finer (a
// dart or a semi-sharp rule breaks eq. 5). At level l itself V0 and its ring
// move freely: the ghost ring follows them. Two interpolating vertices may
// not be neighbours at one level, or one in the other's finer ghost ring:
// their rings would share points. Sharpness set coarser than l that changes V0's rule
// suspends the interpolation (ghostRuleOf) instead; Document::
// setInterpolation refuses to start one on such a vertex.
#pragma once

#include <span>

#include "core/hierarchy/edit.h"
#include "core/hierarchy/ids.h"
#include "core/topology/level.h"
#include "core/util/status.h"

namespace tessera {

// An error naming the interpolating vertex if `candidate` (about to be made
// or redone) conflicts with the active edits in `edits`, or they with it.
Status checkInterpolationConflicts(const Edit& candidate, std::span<const Edit> edits, const Level& base,
                                   const LevelCounts& counts);

// The interpolation edit that decides `vertex` after `edits` (the latest
// active one), or null.
const Edit* decidingInterpolationEdit(std::span<const Edit> edits, VertexId vertex);

}  // namespace tessera
