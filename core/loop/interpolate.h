// Applies one level of Loop refinement to vertex data: given points at
// `parent`, computes points at `child` (which must be refineLevel(parent)).
// Topology is only read, so moving points never rebuilds it.
#pragma once

#include <span>

#include "core/loop/level.h"
#include "core/util/vec3.h"

namespace tessera {

void interpolateLevel(const Level& parent, const Level& child, std::span<const Vec3> parentPoints,
                      std::span<Vec3> childPoints);

}  // namespace tessera
