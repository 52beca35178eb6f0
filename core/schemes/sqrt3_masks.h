// Kobbelt's sqrt(3) subdivision weights (Kobbelt 2000, "sqrt(3)-Subdivision"):
// a new point at each triangle's centroid, old vertices relaxed, old edges
// flipped, so two steps triple the resolution in each direction. Pure.
#pragma once

#include <cmath>
#include <numbers>

namespace tessera::sqrt3 {

inline constexpr double kFacePointWeight = 1.0 / 3.0;

// Relaxation of a vertex of valence n: (1 - alpha) p + alpha/n sum of its
// neighbours, alpha_n = (4 - 2 cos(2 pi / n)) / 9 (alpha_6 = 1/3).
inline double alpha(int n) {
  return (4.0 - 2.0 * std::cos(2.0 * std::numbers::pi / n)) / 9.0;
}

// Limit position: the relaxation's fixed point, beta_n = 3 alpha_n / (1 + 3 alpha_n)
// spread over the neighbours (Kobbelt's eq. 4).
inline double limitNeighbourWeight(int n) {
  return 3.0 * alpha(n) / (1.0 + 3.0 * alpha(n)) / n;
}

}  // namespace tessera::sqrt3
