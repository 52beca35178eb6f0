// The tangent across a Catmull-Clark crease into a span of three or more
// faces (core/catmark/crease_span_tangent.h) against an analysis written
// here from the rules alone: the span's subdivision matrix, with Sdc's
// crease vertex (1/8, 3/4, 1/8) and crease edge (1/2, 1/2) rules and
// Catmull-Clark's face and edge points, must take the mask to the same mask
// times its eigenvalue; the eigenvalues must be the ones numpy's dense
// eigen-solver gave for the same matrix (the largest below 1 of the
// eigenvectors symmetric under a <-> b); and the mask must annihilate
// constants, be symmetric, and point into the span as Limit()'s does.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/catmark/crease_span_tangent.h"
#include "core/catmark/masks.h"

namespace tessera {
namespace {

// Points of a span of k faces: v, then a = e_0, interior e_1..e_{k-1},
// b = e_k, then the opposite corners f_1..f_k (f_i between e_{i-1} and e_i).
struct Span {
  int k;
  int n() const { return 2 * k + 2; }
  int e(int i) const { return 1 + i; }
  int f(int i) const { return k + 1 + i; }
};

// Row r: new point r as a combination of the old points.
std::vector<std::vector<double>> subdivisionMatrix(const Span& s) {
  std::vector<std::vector<double>> m(s.n(), std::vector<double>(s.n(), 0.0));
  m[0][0] = 0.75, m[0][s.e(0)] = 0.125, m[0][s.e(s.k)] = 0.125;
  m[s.e(0)][0] = m[s.e(0)][s.e(0)] = 0.5;
  m[s.e(s.k)][0] = m[s.e(s.k)][s.e(s.k)] = 0.5;
  auto addFacePoint = [&](std::vector<double>& row, int i, double w) {
    row[0] += w / 4, row[s.e(i - 1)] += w / 4, row[s.e(i)] += w / 4, row[s.f(i)] += w / 4;
  };
  for (int i = 1; i <= s.k; ++i) addFacePoint(m[s.f(i)], i, 1.0);
  for (int i = 1; i < s.k; ++i) {
    m[s.e(i)][0] += 0.25, m[s.e(i)][s.e(i)] += 0.25;
    addFacePoint(m[s.e(i)], i, 0.25);
    addFacePoint(m[s.e(i)], i + 1, 0.25);
  }
  return m;
}

std::vector<double> maskOf(const catmark::CreaseSpanTangent& t, const Span& s) {
  std::vector<double> x(s.n(), 0.0);
  x[0] = t.vertex;
  x[s.e(0)] = x[s.e(s.k)] = t.creaseNeighbour;
  for (int i = 1; i < s.k; ++i) x[s.e(i)] = t.interiorNeighbours.at(i - 1);
  for (int i = 1; i <= s.k; ++i) x[s.f(i)] = t.faceCorners.at(i - 1);
  return x;
}

TEST(CreaseSpanTangent, IsALeftEigenvectorOfTheSpansSubdivisionMatrix) {
  for (int k = 3; k <= 40; ++k) {
    SCOPED_TRACE("k = " + std::to_string(k));
    const Span s{k};
    const auto& t = catmark::creaseSpanTangent(k);
    ASSERT_EQ(t.faces, k);
    ASSERT_EQ(static_cast<int>(t.interiorNeighbours.size()), k - 1);
    ASSERT_EQ(static_cast<int>(t.faceCorners.size()), k);
    const std::vector<double> x = maskOf(t, s);
    const auto m = subdivisionMatrix(s);
    double norm = 0, residual = 0, sum = 0;
    for (int c = 0; c < s.n(); ++c) {
      double xm = 0;
      for (int r = 0; r < s.n(); ++r) xm += x[r] * m[r][c];
      residual = std::max(residual, std::abs(xm - t.eigenvalue * x[c]));
      norm = std::max(norm, std::abs(x[c]));
      sum += x[c];
    }
    EXPECT_LE(residual, 1e-12 * norm);
    EXPECT_LE(std::abs(sum), 1e-12 * norm) << "a tangent mask annihilates constants";
    for (int i = 0; i <= k; ++i) EXPECT_NEAR(x[s.e(i)], x[s.e(k - i)], 1e-12 * norm);
    for (int i = 1; i <= k; ++i) EXPECT_NEAR(x[s.f(i)], x[s.f(k + 1 - i)], 1e-12 * norm);
    EXPECT_GT(t.eigenvalue, 0.5) << "above the crease direction's 1/2";
    EXPECT_LT(t.eigenvalue, 2.0 / 3.0);

    // Limit()'s mask for the same span points the same way.
    const catmark::CreaseTangentWeights w = catmark::creaseTangentWeights(k - 1);
    double along = w.vertex * x[0] + 2 * w.creaseNeighbour * x[s.e(0)];
    for (int i = 1; i < k; ++i) along += w.interiorNeighbour(i) * x[s.e(i)];
    for (int i = 1; i <= k; ++i) along += w.face(i - 1) * x[s.f(i)];
    EXPECT_GT(along, 0);
  }
}

TEST(CreaseSpanTangent, EigenvaluesAreTheLargestSymmetricOnesBelowOne) {
  // numpy.linalg.eig of the same matrices (an analysis outside the code
  // under test, docs/LIMITS.md "Catmull-Clark limits").
  const std::vector<std::pair<int, double>> expected = {{3, 0.579682326102}, {4, 0.611116526695},
                                                        {5, 0.626341267547}, {6, 0.634796412354},
                                                        {8, 0.643334922473}, {12, 0.649515097431}};
  for (const auto& [k, lambda] : expected)
    EXPECT_NEAR(catmark::creaseSpanTangent(k).eigenvalue, lambda, 1e-11) << k;
}

}  // namespace
}  // namespace tessera
