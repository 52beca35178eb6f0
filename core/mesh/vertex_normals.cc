#include "core/mesh/vertex_normals.h"

#include <cmath>

namespace tessera {

std::vector<Vec3> areaWeightedVertexNormals(std::span<const Vec3> points,
                                            std::span<const std::array<int, 3>> triangles) {
  std::vector<Vec3> normals(points.size(), Vec3(0, 0, 0));
  for (const auto& t : triangles) {
    // The cross product's length is twice the area: larger faces weigh more.
    const Vec3 n = (points[t[1]] - points[t[0]]) % (points[t[2]] - points[t[0]]);
    for (int v : t) normals[v] += n;
  }
  for (Vec3& n : normals) {
    const double len2 = n.sqrnorm();
    n = len2 > 0.0 ? (1.0 / std::sqrt(len2)) * n : Vec3(0, 0, 0);
  }
  return normals;
}

}  // namespace tessera
