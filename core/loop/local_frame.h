// Local frames for detail offsets (Pulli & Lounsbery, "Hierarchical Editing
// and Rendering of Subdivision Surfaces" §2.3, §4.3).
//
// Fine-level edits are stored as offsets in a frame that follows the surface,
// so detail moves along when coarser levels change. The paper builds the
// frame from the *smooth-rule* normal whatever the vertex type (a crease or
// corner has no unique normal, but the smooth rule always gives one that
// follows the surface) and fixes the rotation about it by starting the
// tangent sum at a consistently chosen neighbour. Tessera's rings are ordered
// canonically from the base mesh (level.h), so ring neighbour 0 is the same
// vertex in every process and after every reload: frames are reproducible
// and offsets can be persisted in local coordinates.
#pragma once

#include <span>

#include "core/topology/level.h"
#include "core/util/vec3.h"

namespace tessera {

struct LocalFrame {
  Vec3 tangent;    // unit, in the direction of ring neighbour 0's tangent weight
  Vec3 bitangent;  // unit, normal x tangent
  Vec3 normal;     // unit, the smooth-rule (or boundary-rule) limit normal

  Vec3 toWorld(const Vec3& local) const {
    return local[0] * tangent + local[1] * bitangent + local[2] * normal;
  }
  Vec3 toLocal(const Vec3& world) const {
    return {dot(world, tangent), dot(world, bitangent), dot(world, normal)};
  }
};

// Interior vertices use Loop's smooth tangent masks over the whole ring;
// boundary vertices the boundary tangents across their faces. A degenerate
// neighbourhood (coincident points) falls back to the world axes.
LocalFrame localFrame(const Level& level, Index v, std::span<const Vec3> points);

}  // namespace tessera
