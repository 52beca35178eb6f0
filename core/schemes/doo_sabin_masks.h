// Doo-Sabin's weights (Doo & Sabin '78, "Behaviour of Recursive Division
// Surfaces near Extraordinary Points"): the dual,
// biquadratic scheme. Each face of n corners yields a new point per corner,
// a fixed mix of that face's corners. Pure functions.
#pragma once

#include <cmath>
#include <numbers>

namespace tessera::doosabin {

// New point for corner i of an n-gon: corner j weighs
// (3 + 2 cos(2 pi (i - j) / n)) / (4 n), plus 1/4 for j = i. On quads this is
// 9/16, 3/16, 3/16, 1/16: the tensor product of Chaikin's (3/4, 1/4).
inline double cornerWeight(int n, int distance) {
  return (3.0 + 2.0 * std::cos(2.0 * std::numbers::pi * distance / n)) / (4.0 * n) +
         (distance == 0 ? 0.25 : 0.0);
}

// The weights form a circulant matrix with eigenvalues 1 (the centroid),
// 1/2 (the first Fourier modes) and 1/4: every face keeps its centroid and
// shrinks onto it, so the centroid is the limit point of the face, and the
// first Fourier modes, sum cos(2 pi k / n) p_k and sum sin(2 pi k / n) p_k,
// span the limit tangent plane there.
inline double tangentCosWeight(int n, int k) {
  return std::cos(2.0 * std::numbers::pi * k / n);
}
inline double tangentSinWeight(int n, int k) {
  return std::sin(2.0 * std::numbers::pi * k / n);
}

}  // namespace tessera::doosabin
