// The one 3-vector type of core: OpenMesh's, since the base mesh is OpenMesh.
#pragma once

#include <OpenMesh/Core/Geometry/VectorT.hh>

namespace tessera {

using Vec3 = OpenMesh::Vec3d;

inline bool isFinite(const Vec3& p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

}  // namespace tessera
