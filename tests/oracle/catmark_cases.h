// What the Catmull-Clark oracle tests share (header only): the option sets
// they run under and the scale their tolerances are relative to.
#pragma once

#include <algorithm>
#include <vector>

#include "core/catmark/dart_masks.h"
#include "core/catmark/polygon_level.h"
#include "core/catmark/semi_sharp_limit.h"
#include "core/loop/exact_limit.h"
#include "core/topology/level.h"
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

// Where Far's Limit() is not the Catmull-Clark surface's limit and Tessera's
// is, so the tests against Limit() leave them to bfr_catmark_limit_test.cc,
// which holds them to Bfr's convergence (docs/LIMITS.md "Catmull-Clark
// limits"):
// - a dart's position and normal: Limit() takes the smooth masks there,
//   Tessera the dart ring's own eigenvectors (core/catmark/dart_masks.h);
// - a vertex where a semi-sharp feature has not decayed: Limit() counts it
//   as sharp, Tessera refines the ring until it has decayed
//   (core/catmark/semi_sharp_limit.h);
inline bool limitPositionDiffersFromFar(const Level& level, Index v, const CreaseOptions& options) {
  if (takesDecayedLimit(level, v, options)) return true;
  return level.vertexRules[v] == VertexRule::kDart && catmark::hasExactDartMasks(level.valence(v));
}
// - and the normal of a crease vertex (a boundary one too) whose first
//   side, the one catmarkLimitFrame's tangents give, spans three faces or
//   more: Limit() takes Biermann et al.'s tangent across, Tessera the side's
//   own eigenvector (core/catmark/crease_span_tangent.h).
inline bool limitNormalDiffersFromFar(const Level& level, Index v, const CreaseOptions& options) {
  if (limitPositionDiffersFromFar(level, v, options)) return true;
  if (level.vertexRules[v] != VertexRule::kCrease) return false;
  const std::vector<int> sharp = sharpRingEdges(level, v);
  return sharp.size() >= 2 && sharp[1] - sharp[0] >= 3;
}

}  // namespace tessera::oracle
