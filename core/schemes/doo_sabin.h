// Doo-Sabin refinement of polygon meshes (on the Level topology). Child
// numbering: one vertex per parent face corner (faceBegin(f) + i). Child
// faces, in this order: one per parent face (its corners' points), one quad
// per interior edge, one polygon per interior vertex (its faces' points in
// ring order). Boundary edges and vertices get no face: the mesh's border
// retreats to the boundary faces' new points, as in the original scheme
// without boundary rules.
#pragma once

#include <span>
#include <vector>

#include "core/catmark/polygon_level.h"
#include "core/topology/level.h"
#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera::schemes {

struct PolygonRefinement {
  PolyTopology topology;  // the finest level's faces
  std::vector<Vec3> points;
};

// One Doo-Sabin step: child points and faces from a parent level.
PolygonRefinement dooSabinStep(const Level& parent, std::span<const Vec3> parentPoints);

// `levels` steps; tags are ignored (Doo-Sabin has no crease rules here).
Expected<PolygonRefinement> refineDooSabin(const PolyTopology& topology, std::span<const Vec3> points,
                                           int levels, long long maxFaces = 16LL * 1024 * 1024);

// The limit point and normal of each face (doo_sabin_masks.h): its centroid,
// and the normal of its first Fourier modes (unit, zero if degenerate).
void dooSabinFaceLimits(const PolyTopology& topology, std::span<const Vec3> points,
                        std::vector<Vec3>& positions, std::vector<Vec3>& normals);

}  // namespace tessera::schemes
