// Loop's subdivision and limit weights (Loop '87; limit and tangent masks as
// in OpenSubdiv's sdc/loopScheme.h, with Hoppe et al. '94 for creases).
// Pure functions of valence: no mesh, no storage.
#pragma once

#include <cmath>
#include <numbers>

namespace tessera::loop {

// Weight of each ring neighbour for a smooth vertex of valence n:
// beta(n) = (5/8 - (3/8 + 1/4 cos(2 pi / n))^2) / n. Valence 6 gives 1/16.
inline double smoothEdgeWeight(int n) {
  if (n == 6) return 1.0 / 16.0;
  const double c = 0.375 + 0.25 * std::cos(2.0 * std::numbers::pi / n);
  return (0.625 - c * c) / n;
}

// Limit position of a smooth vertex: each neighbour weighs
// 1 / (n + 3 / (8 beta)); the vertex takes the rest. Valence 6 gives 1/12.
inline double smoothLimitEdgeWeight(int n) {
  if (n == 6) return 1.0 / 12.0;
  return 1.0 / (n + 3.0 / (8.0 * smoothEdgeWeight(n)));
}

// Crease vertex (1/8, 3/4, 1/8) refines a uniform cubic B-spline along the
// crease, whose limit mask is (1/6, 2/3, 1/6) whatever the valence.
inline constexpr double kCreaseVertexWeight = 0.75;
inline constexpr double kCreaseNeighbourWeight = 0.125;
inline constexpr double kCreaseLimitVertexWeight = 4.0 / 6.0;
inline constexpr double kCreaseLimitNeighbourWeight = 1.0 / 6.0;

// Smooth edge vertex: 3/8 for the ends, 1/8 for the two opposite vertices.
inline constexpr double kEdgeEndWeight = 0.375;
inline constexpr double kEdgeOppositeWeight = 0.125;

}  // namespace tessera::loop
