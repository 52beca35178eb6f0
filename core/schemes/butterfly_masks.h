// The modified Butterfly scheme's weights (Dyn, Levin & Gregory '90, "A
// Butterfly Subdivision Scheme for Surface Interpolation with Tension
// Control"; Zorin, Schroeder & Sweldens '96, "Interpolating Subdivision for
// Meshes with Arbitrary Topology"): an interpolating scheme, so
// old vertices stay and only edge points are computed. Pure functions.
#pragma once

#include <cmath>
#include <numbers>

namespace tessera::butterfly {

// Regular edge (both ends of valence 6, or on a boundary): the 8-point
// butterfly with w = 0: 1/2 for the ends, 1/8 for the two opposite
// vertices, -1/16 for the four wing tips.
inline constexpr double kEndWeight = 0.5;
inline constexpr double kOppositeWeight = 0.125;
inline constexpr double kWingWeight = -1.0 / 16.0;

// A boundary edge: the 4-point curve rule (9/16, 9/16, -1/16, -1/16).
inline constexpr double kBoundaryEndWeight = 9.0 / 16.0;
inline constexpr double kBoundaryOuterWeight = -1.0 / 16.0;

// An interior end of valence k != 6 (Zorin et al.): ring neighbour j, counted
// from the edge's other end, weighs s_j; the vertex takes 3/4.
//   k = 3: 5/12, -1/12, -1/12;  k = 4: 3/8, 0, -1/8, 0;
//   k >= 5: (1/4 + cos(2 pi j / k) + 1/2 cos(4 pi j / k)) / k.
inline double irregularNeighbourWeight(int k, int j) {
  if (k == 3) return j == 0 ? 5.0 / 12.0 : -1.0 / 12.0;
  if (k == 4) return j == 0 ? 3.0 / 8.0 : (j == 2 ? -1.0 / 8.0 : 0.0);
  const double t = 2.0 * std::numbers::pi * j / k;
  return (0.25 + std::cos(t) + 0.5 * std::cos(2.0 * t)) / k;
}
inline constexpr double kIrregularVertexWeight = 0.75;

}  // namespace tessera::butterfly
