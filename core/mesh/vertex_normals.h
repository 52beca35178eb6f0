// Vertex normals of a triangle mesh by area-weighted face normals: the
// normals exported with control-point surfaces, where no limit normal exists.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "core/util/vec3.h"

namespace tessera {

// One unit normal per point (zero for a point no non-degenerate face uses).
std::vector<Vec3> areaWeightedVertexNormals(std::span<const Vec3> points,
                                            std::span<const std::array<int, 3>> triangles);

}  // namespace tessera
