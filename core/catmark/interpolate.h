// Catmull-Clark refinement of vertex data: the child level's points from the
// parent's, with semi-sharp creases blended as OpenSubdiv's Sdc does. The
// child level (quad_split.h) supplies what the parent's features become.
#pragma once

#include <span>

#include "core/topology/level.h"
#include "core/util/vec3.h"

namespace tessera {

// `childPoints` holds child.numVertices points (quad_split.h numbering).
void interpolateCatmark(const Level& parent, const Level& child, std::span<const Vec3> parentPoints,
                        std::span<Vec3> childPoints);

}  // namespace tessera
