// What the Catmull-Clark oracle tests share (header only): the option sets
// they run under and the scale their tolerances are relative to.
#pragma once

#include <algorithm>
#include <vector>

#include "core/catmark/polygon_level.h"
#include "core/util/vec3.h"

namespace tessera::oracle {

// Against Far: refined points within this much of the bounding-box
// diagonal, Limit() positions too, limit normals within this many radians.
inline constexpr double kPointTolerance = 1e-12;
inline constexpr double kPositionTolerance = 1e-9;
inline constexpr double kNormalTolerance = 1e-6;

// Both crease methods under both boundary rules.
inline std::vector<CreaseOptions> allCreaseOptions() {
  std::vector<CreaseOptions> all;
  for (auto method : {CreaseMethod::kUniform, CreaseMethod::kChaikin}) {
    for (auto boundary : {BoundaryInterpolation::kEdgeOnly, BoundaryInterpolation::kEdgeAndCorner}) {
      all.push_back({method, boundary});
    }
  }
  return all;
}

// The diagonal of the points' bounding box.
inline double boundingDiagonal(const std::vector<Vec3>& points) {
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  }
  return (hi - lo).norm();
}

}  // namespace tessera::oracle
