// A refined or limit surface as plain arrays: what refinement, evaluation and
// tessellation produce and what every exporter and codec consumes. It lives
// with the base mesh, below both, so producing a surface never means
// including an exporter.
#pragma once

#include <array>
#include <vector>

#include "core/util/vec3.h"

namespace tessera {

struct SurfaceMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;                  // empty, or one unit normal per position
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise
};

}  // namespace tessera
