// A level's sharp features as a cage states them (core/mesh/surface_mesh.h):
// every edge and vertex whose sharpness at this level is not smooth, with
// that sharpness (semi-sharp values as refinement decayed them, infinitely
// sharp as kSharpnessInfinite, boundary edges included as the level holds
// them). Refined by the same rules, the cage and the level agree.
#pragma once

#include "core/mesh/surface_mesh.h"
#include "core/topology/level.h"

namespace tessera {

void addCageTags(const Level& level, SurfaceMesh& surface);

}  // namespace tessera
