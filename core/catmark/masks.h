// Catmull-Clark's subdivision and limit weights (Catmull & Clark '78,
// "Recursively Generated B-spline Surfaces on Arbitrary Topological Meshes"),
// with the crease masks of DeRose, Kass & Truong '98 and the limit and
// tangent masks of OpenSubdiv 3.5's sdc/catmarkScheme.h
// (Halstead et al. '93 for the smooth limit, Biermann et al. '00 for the
// tangent across a crease). Pure functions of valence: no mesh, no storage.
#pragma once

#include <cmath>
#include <numbers>

namespace tessera::catmark {

// Face point: the centroid of the face's corners.
inline double facePointWeight(int faceSize) {
  return 1.0 / faceSize;
}

// Smooth edge point: the mean of its two ends and the two adjacent face
// points (1/4 each).
inline constexpr double kEdgeEndWeight = 0.25;
inline constexpr double kEdgeFaceWeight = 0.25;

// Smooth vertex point of valence n: (n-2)/n of the vertex plus 1/n^2 of each
// ring neighbour and 1/n^2 of each adjacent face point -- the B-spline's
// (Q + 2R + (n-3)S)/n written per neighbour, since each edge midpoint R holds
// the vertex and one neighbour.
inline double smoothVertexWeight(int n) {
  return static_cast<double>(n - 2) / n;
}
inline double smoothNeighbourWeight(int n) {
  return 1.0 / (static_cast<double>(n) * n);
}

// Crease vertex: (1/8, 3/4, 1/8) along the crease, a cubic B-spline curve.
inline constexpr double kCreaseVertexWeight = 0.75;
inline constexpr double kCreaseNeighbourWeight = 0.125;

// Limit position of a smooth vertex (the dominant left eigenvector of the
// subdivision matrix): each face's opposite corner weighs 1/(n(n+5)), each
// ring neighbour 4/(n(n+5)), the vertex n/(n+5). Valence 4 gives the bicubic
// B-spline's 1/36, 1/9, 4/9.
inline double smoothLimitFaceWeight(int n) {
  return 1.0 / (static_cast<double>(n) * (n + 5));
}
inline double smoothLimitNeighbourWeight(int n) {
  return 4.0 * smoothLimitFaceWeight(n);
}
inline double smoothLimitVertexWeight(int n) {
  return static_cast<double>(n) / (n + 5);
}

// Crease limit: the cubic B-spline's (1/6, 2/3, 1/6).
inline constexpr double kCreaseLimitVertexWeight = 2.0 / 3.0;
inline constexpr double kCreaseLimitNeighbourWeight = 1.0 / 6.0;

// Smooth tangent masks of valence n != 4 (the subdominant eigenvectors):
// ring neighbour k weighs 4 cos(2 pi k / n), the opposite corner of face k
// weighs (cos(2 pi k/n) + cos(2 pi (k+1)/n)) / (4 lambda - 1), lambda being
// the subdominant eigenvalue. The second tangent is the first rotated by one.
inline double smoothTangentLambda(int n) {
  const double theta = 2.0 * std::numbers::pi / n;
  return 5.0 / 16.0 +
         (std::cos(theta) + std::cos(0.5 * theta) * std::sqrt(2.0 * (9.0 + std::cos(theta)))) / 16.0;
}
inline double smoothTangentNeighbourWeight(int n, int k) {
  return 4.0 * std::cos(2.0 * std::numbers::pi * k / n);
}
inline double smoothTangentFaceWeight(int n, int k) {
  const double theta = 2.0 * std::numbers::pi / n;
  return (std::cos(k * theta) + std::cos((k + 1) * theta)) / (4.0 * smoothTangentLambda(n) - 1.0);
}

// The tangent across a crease whose span holds `interior` interior edges
// (Biermann et al.; valence 4's regular case is the B-spline's cross
// derivative), oriented into the span. Weights of the vertex, of the two
// crease neighbours, of interior neighbour i (1..interior) and of the
// opposite corner of span face i (0..interior).
struct CreaseTangentWeights {
  double vertex;
  double creaseNeighbour;
  double interiorNeighbour(int i) const;
  double face(int i) const;
  int interior;
  double theta, denominator;
};
inline CreaseTangentWeights creaseTangentWeights(int interior) {
  CreaseTangentWeights w{};
  w.interior = interior;
  if (interior == 1) {
    w.vertex = -4.0 / 6.0;
    w.creaseNeighbour = -1.0 / 6.0;
    return w;
  }
  if (interior == 0) {  // one face: the mean of the two boundary edges
    w.vertex = -6.0;
    w.creaseNeighbour = 3.0;
    return w;
  }
  const double k = interior + 1;
  w.theta = std::numbers::pi / k;
  const double c = std::cos(w.theta), s = std::sin(w.theta);
  w.denominator = 1.0 / (k * (3.0 + c));
  const double r = (c + 1.0) / s;
  w.vertex = 4.0 * r * (c - 1.0) * w.denominator;
  w.creaseNeighbour = -r * (1.0 + 2.0 * c) * w.denominator;
  return w;
}
inline double CreaseTangentWeights::interiorNeighbour(int i) const {
  if (interior == 1) return 4.0 / 6.0;
  return 4.0 * std::sin(i * theta) * denominator;
}
inline double CreaseTangentWeights::face(int i) const {
  if (interior == 1) return 1.0 / 6.0;
  if (interior == 0) return 0.0;
  return (std::sin(i * theta) + std::sin((i + 1) * theta)) * denominator;
}

}  // namespace tessera::catmark
