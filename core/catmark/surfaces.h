// Surfaces of one level of a quad split, ready to draw or export: the
// control polygons as they are (quads below the base, any polygon at it),
// or Catmull-Clark's limit positions and normals at every vertex. Each
// keeps its polygons beside their fan triangles (core/mesh/surface_mesh.h).
#pragma once

#include <span>

#include "core/catmark/polygon_level.h"
#include "core/mesh/surface_mesh.h"
#include "core/topology/level.h"
#include "core/util/status.h"

namespace tessera {

// Positions and polygons, no normals.
SurfaceMesh polygonSurfaceOf(const Level& level, std::span<const Vec3> points);
// Positions, polygons and area-weighted vertex normals of the fans.
SurfaceMesh polygonControlSurfaceOf(const Level& level, std::span<const Vec3> points);
// Needs an all-quad level with its full topology (core/catmark/limit.h);
// otherwise an error that says to refine once.
Expected<SurfaceMesh> catmarkLimitSurfaceOf(const Level& level, const CreaseOptions& options,
                                            std::span<const Vec3> points);

}  // namespace tessera
