#include "core/mesh/crease_angle.h"

#include <cmath>
#include <span>
#include <unordered_map>
#include <vector>

#include "core/mesh/polygon_triangulation.h"

namespace tessera {

Expected<int> creaseByDihedralAngle(const PolygonSoup& soup, double degrees, BaseMesh& mesh) {
  if (!(degrees >= 0 && degrees <= 180)) {
    return invalidArgument("crease angle " + std::to_string(degrees) + ": expects degrees from 0 to 180");
  }
  const double limit = degrees * M_PI / 180.0;
  std::vector<Vec3> normals(soup.numFaces());
  for (int f = 0; f < soup.numFaces(); ++f) {
    const std::span<const int> corners(soup.indices.data() + soup.faceOffsets[f],
                                       soup.faceOffsets[f + 1] - soup.faceOffsets[f]);
    normals[f] = polygonNormal(soup.points, corners);
  }
  // Edge (low, high) -> the faces on it; -1 while only one is known.
  std::unordered_map<uint64_t, std::pair<int, int>> faces;
  faces.reserve(soup.indices.size());
  for (int f = 0; f < soup.numFaces(); ++f) {
    const int begin = soup.faceOffsets[f], end = soup.faceOffsets[f + 1];
    for (int k = begin; k < end; ++k) {
      int a = soup.indices[k], b = soup.indices[k + 1 < end ? k + 1 : begin];
      if (a > b) std::swap(a, b);
      const uint64_t key = (static_cast<uint64_t>(a) << 32) | static_cast<uint32_t>(b);
      auto [it, inserted] = faces.emplace(key, std::pair<int, int>(f, -1));
      if (!inserted) it->second.second = f;
    }
  }
  int creased = 0;
  for (const auto& [key, pair] : faces) {
    if (pair.second < 0) continue;  // a boundary edge
    const Vec3& n0 = normals[pair.first];
    const Vec3& n1 = normals[pair.second];
    // atan2 of |sin| and cos: accurate at every angle, unlike acos near 0.
    const double angle = std::atan2((n0 % n1).norm(), n0 | n1);
    if (angle <= limit) continue;
    TESSERA_RETURN_IF_ERROR(mesh.setCreaseByVertices(
        static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffffu), kSharpnessInfinite));
    ++creased;
  }
  return creased;
}

}  // namespace tessera
