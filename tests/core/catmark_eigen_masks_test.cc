// The Catmull-Clark masks Tessera takes from a neighbourhood's own
// subdivision matrix, where OpenSubdiv's Limit() masks are not the
// surface's: the tangent across a crease into three faces or more
// (core/catmark/crease_span_tangent.h) and a dart's limit and tangents
// (core/catmark/dart_masks.h). Each is held to an analysis written here from
// the rules alone: the neighbourhood's subdivision matrix, with Sdc's crease
// vertex (1/8, 3/4, 1/8) and crease edge (1/2, 1/2) rules, the smooth vertex
// rule and Catmull-Clark's face and edge points, must take the mask to the
// same mask times its eigenvalue; the eigenvalues must be the ones numpy's
// dense eigen-solver gave for the same matrices (the largest below 1 among
// the eigenvectors symmetric, or antisymmetric, across the crease or the
// dart edge); and the masks must have the symmetry and the sums they claim.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/catmark/crease_span_tangent.h"
#include "core/catmark/dart_masks.h"
#include "core/catmark/limit.h"
#include "core/catmark/masks.h"
#include "core/schemes/quad_refiner.h"

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

// A dart's one-ring: v, neighbours e_0..e_{n-1} (e_0 across the dart
// edge), opposite corners f_0..f_{n-1} (f_i between e_i and e_{i+1}).
struct Ring {
  int n;
  int size() const { return 2 * n + 1; }
  int e(int i) const { return 1 + ((i % n) + n) % n; }
  int f(int i) const { return 1 + n + ((i % n) + n) % n; }
};

std::vector<std::vector<double>> dartMatrix(const Ring& r) {
  const int n = r.n;
  std::vector<std::vector<double>> m(r.size(), std::vector<double>(r.size(), 0.0));
  auto addFacePoint = [&](std::vector<double>& row, int i, double w) {
    row[0] += w / 4, row[r.e(i)] += w / 4, row[r.f(i)] += w / 4, row[r.e(i + 1)] += w / 4;
  };
  // The smooth vertex point: (n-2)/n v + 1/n^2 of each neighbour and of
  // each new face point.
  m[0][0] = (n - 2.0) / n;
  for (int i = 0; i < n; ++i) {
    m[0][r.e(i)] += 1.0 / (n * n);
    addFacePoint(m[0], i, 1.0 / (n * n));
    addFacePoint(m[r.f(i)], i, 1.0);
  }
  m[r.e(0)][0] = m[r.e(0)][r.e(0)] = 0.5;  // the dart edge's midpoint
  for (int i = 1; i < n; ++i) {
    m[r.e(i)][0] += 0.25, m[r.e(i)][r.e(i)] += 0.25;
    addFacePoint(m[r.e(i)], i - 1, 0.25);
    addFacePoint(m[r.e(i)], i, 0.25);
  }
  return m;
}

std::vector<double> ringMask(const catmark::DartMask& mask, const Ring& r) {
  std::vector<double> x(r.size(), 0.0);
  x[0] = mask.vertex;
  for (int i = 0; i < r.n; ++i) x[r.e(i)] = mask.neighbours.at(i), x[r.f(i)] = mask.faceCorners.at(i);
  return x;
}

// max |x S - lambda x| / max |x|.
double eigenResidual(const std::vector<double>& x, const std::vector<std::vector<double>>& m, double lambda) {
  double norm = 0, residual = 0;
  for (size_t c = 0; c < x.size(); ++c) {
    double xm = 0;
    for (size_t row = 0; row < x.size(); ++row) xm += x[row] * m[row][c];
    residual = std::max(residual, std::abs(xm - lambda * x[c]));
    norm = std::max(norm, std::abs(x[c]));
  }
  return residual / norm;
}

TEST(DartMasks, AreLeftEigenvectorsOfTheDartRingsSubdivisionMatrix) {
  for (int n = 3; n <= 30; ++n) {
    SCOPED_TRACE("valence " + std::to_string(n));
    const Ring r{n};
    const auto m = dartMatrix(r);
    const catmark::DartMasks& d = catmark::dartMasks(n);
    const auto limit = ringMask(d.limit, r), along = ringMask(d.along, r), across = ringMask(d.across, r);
    EXPECT_LE(eigenResidual(limit, m, 1.0), 1e-12);
    EXPECT_LE(eigenResidual(along, m, d.alongEigenvalue), 1e-12);
    EXPECT_LE(eigenResidual(across, m, d.acrossEigenvalue), 1e-12);
    double limitSum = 0, alongSum = 0, acrossSum = 0;
    for (int j = 0; j < r.size(); ++j) limitSum += limit[j], alongSum += along[j], acrossSum += across[j];
    EXPECT_NEAR(limitSum, 1.0, 1e-12);
    EXPECT_NEAR(alongSum, 0.0, 1e-12);
    EXPECT_NEAR(acrossSum, 0.0, 1e-12);
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(limit[r.e(i)], limit[r.e(-i)], 1e-12);
      EXPECT_NEAR(along[r.e(i)], along[r.e(-i)], 1e-12);
      EXPECT_NEAR(across[r.e(i)], -across[r.e(-i)], 1e-12);
      EXPECT_NEAR(along[r.f(i)], along[r.f(-1 - i)], 1e-12);
      EXPECT_NEAR(across[r.f(i)], -across[r.f(-1 - i)], 1e-12);
    }
    EXPECT_GT(along[r.e(0)], 0) << "along points towards the dart edge";
    EXPECT_GT(across[r.e(1)], 0) << "across points towards neighbour 1";
  }
}

TEST(DartMasks, EigenvaluesAndTheLimitWeightAreNumpys) {
  // numpy.linalg.eig of the same matrices, restricted to the symmetric and
  // antisymmetric vectors (an analysis outside the code under test,
  // docs/LIMITS.md "Catmull-Clark limits"): valence, along, across, the
  // vertex's limit weight.
  struct Expected {
    int n;
    double along, across, vertex;
  };
  for (const Expected& e :
       {Expected{3, 0.462060590538, 0.410097050801, 0.405000000000}, Expected{4, 0.5, 0.5, 0.467661691542},
        Expected{5, 0.526424362162, 0.549988354518, 0.518549747049},
        Expected{6, 0.548221624015, 0.579682326102, 0.560650029019},
        Expected{8, 0.581909960445, 0.611116526695, 0.626154800958},
        Expected{12, 0.617652942507, 0.634796412354, 0.712126918423}}) {
    const catmark::DartMasks& d = catmark::dartMasks(e.n);
    EXPECT_NEAR(d.alongEigenvalue, e.along, 1e-11) << e.n;
    EXPECT_NEAR(d.acrossEigenvalue, e.across, 1e-11) << e.n;
    EXPECT_NEAR(d.limit.vertex, e.vertex, 1e-11) << e.n;
  }
}

// A fan of n quads around one vertex whose first edge is infinitely sharp:
// a dart of valence n.
struct Fan {
  PolyTopology topology;
  std::vector<Vec3> points;
};
Fan dartFan(int n) {
  Fan fan;
  fan.topology.numVertices = 1 + 2 * n;
  fan.points.push_back(Vec3(0, 0, 0.2));
  for (int j = 0; j < 2 * n; ++j) {
    const double angle = std::numbers::pi * j / n, radius = j % 2 ? 1.3 : 1.0;
    fan.points.push_back(Vec3(radius * std::cos(angle), radius * std::sin(angle), 0.05 * std::sin(3.0 * j)));
  }
  auto ring = [&](int j) { return 1 + j % (2 * n); };
  for (int i = 0; i < n; ++i) {
    const std::array<int, 4> quad = {0, ring(2 * i), ring(2 * i + 1), ring(2 * i + 2)};
    fan.topology.addFace(quad);
  }
  fan.topology.creases.push_back({0, ring(0), 10.0f});
  return fan;
}

// Limit()'s smooth position mask, written out.
Vec3 smoothLimit(const Fan& fan, int n) {
  Vec3 edges(0, 0, 0), corners(0, 0, 0);
  for (int i = 0; i < n; ++i) edges += fan.points[1 + 2 * i], corners += fan.points[2 + 2 * i];
  const double w = 1.0 / (n * (n + 5.0));
  return (n / (n + 5.0)) * fan.points[0] + 4.0 * w * edges + w * corners;
}

TEST(DartMasks, AboveTheirLargestValenceDartsTakeLimitsSmoothMasks) {
  for (int n : {catmark::kMaxExactDartValence, catmark::kMaxExactDartValence + 1, 500}) {
    SCOPED_TRACE("valence " + std::to_string(n));
    const Fan fan = dartFan(n);
    auto refiner =
        schemes::QuadRefiner::create(fan.topology, schemes::QuadScheme::kCatmullClark, {}, {.levels = 1});
    ASSERT_TRUE(refiner.isOk()) << refiner.status().toString();
    const Level& level = refiner->level(0);
    ASSERT_EQ(level.vertexRules[0], VertexRule::kDart);
    ASSERT_EQ(level.valence(0), n);
    const double off = (catmarkLimitFrame(level, 0, fan.points, {}).position - smoothLimit(fan, n)).norm();
    if (catmark::hasExactDartMasks(n)) {
      EXPECT_GT(off, 1e-6) << "the dart's own limit";
    } else {
      EXPECT_LE(off, 1e-12) << "Limit()'s smooth mask";
      EXPECT_NEAR(catmarkSelfLimitWeight(level, 0, {}), n / (n + 5.0), 1e-15);
    }
  }
}

}  // namespace
}  // namespace tessera
