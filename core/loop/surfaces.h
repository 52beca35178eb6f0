// Surfaces of one level, ready to draw or export: control points with
// area-weighted normals, or the limit surface with exact limit normals in
// which crease and corner vertices are split, one copy per side with that
// side's normal (copies appended after the level's vertices, so vertex
// numbering is unchanged).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "core/loop/loop_options.h"
#include "core/mesh/surface_mesh.h"
#include "core/topology/level.h"
#include "core/util/status.h"

namespace tessera {

// The faces of a level of triangles, as meshes and exporters take them.
std::vector<std::array<int, 3>> trianglesOf(const Level& level);

SurfaceMesh controlSurfaceOf(const Level& level, std::span<const Vec3> points);
// Needs the level's full topology (rings).
Expected<SurfaceMesh> limitSurfaceOf(const Level& level, std::span<const Vec3> points, CreaseMethod method);

}  // namespace tessera
