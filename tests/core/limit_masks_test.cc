// Exact limit masks (core/loop/limit_masks.h) against definitions:
//  * the matrix is the lone-ring step (itself checked against whole-mesh
//    refinement in local_ring_test.cc);
//  * the position mask is a fixed point of the matrix, and the limit of
//    refining the ring many times;
//  * a tangent plane is the plane the refined ring flattens into: after many
//    steps every ring point's offset from the limit lies in it, and the
//    ring's faces turn counter-clockwise about its normal;
//  * which sectors have no tangent plane follows from the eigenvalues known
//    in closed form (1, 1/2, 1/4 of the crease curve; 3/8 + cos(j pi/k)/4 of
//    a k-face sector's interior; 3/8 + cos(2 pi j/n)/4 of a cusp's ring).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <numbers>
#include <random>

#include "core/loop/limit_masks.h"
#include "core/loop/local_ring.h"
#include "core/mesh/sharpness.h"

namespace tessera {
namespace {

std::vector<StationaryRing> configurations() {
  std::vector<StationaryRing> rings;
  auto make = [](int n, bool boundary, VertexRule rule, std::vector<int> sharp) {
    StationaryRing r{n, boundary, rule, std::vector<bool>(n, false)};
    for (int k : sharp) r.sharpEdges[k] = true;
    return r;
  };
  for (int n = 3; n <= 12; ++n) {
    rings.push_back(make(n, false, VertexRule::kSmooth, {}));
    rings.push_back(make(n, false, VertexRule::kDart, {0}));
    rings.push_back(make(n, false, VertexRule::kDart, {n / 2}));
    rings.push_back(make(n, false, VertexRule::kCorner, {}));   // a cusp
    rings.push_back(make(n, false, VertexRule::kCorner, {1}));  // a cusp on a dart edge
    for (int b = 1; b < n; ++b) rings.push_back(make(n, false, VertexRule::kCrease, {0, b}));
    if (n >= 3) rings.push_back(make(n, false, VertexRule::kCorner, {0, 1, n / 2 + 1}));
  }
  for (int n = 2; n <= 11; ++n) {
    rings.push_back(make(n, true, VertexRule::kCrease, {0, n - 1}));
    rings.push_back(make(n, true, VertexRule::kCorner, {0, n - 1}));
    if (n >= 4) rings.push_back(make(n, true, VertexRule::kCorner, {0, n / 2, n - 1}));
  }
  return rings;
}

std::string describe(const StationaryRing& r) {
  std::string s = "valence " + std::to_string(r.valence) + (r.boundary ? " boundary" : " interior") +
                  " rule " + std::to_string(static_cast<int>(r.rule)) + " sharp";
  for (int k = 0; k < r.valence; ++k) {
    if (r.sharpEdges[k]) s += " " + std::to_string(k);
  }
  return s;
}

LocalRing lone(const StationaryRing& r, const std::vector<Vec3>& points) {
  LocalRing ring;
  ring.valence = r.valence;
  ring.boundary = r.boundary;
  ring.rule = r.rule;
  ring.vertexSharpness = r.rule == VertexRule::kCorner ? kSharpnessInfinite : kSharpnessSmooth;
  for (bool sharp : r.sharpEdges) ring.edgeSharpness.push_back(sharp ? kSharpnessInfinite : kSharpnessSmooth);
  ring.farRingSharpness.assign(r.valence, {});
  ring.points = points;
  ring.centreWeight.assign(points.size(), 0.0);
  return ring;
}

std::vector<Vec3> randomRing(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  std::vector<Vec3> p{Vec3(u(rng), u(rng), 0.4 + u(rng))};
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    p.push_back(Vec3(std::cos(a) + u(rng), std::sin(a) + u(rng), u(rng)));
  }
  return p;
}

Vec3 applyMask(const std::vector<double>& mask, const std::vector<Vec3>& p) {
  Vec3 s(0, 0, 0);
  for (size_t i = 0; i < p.size(); ++i) s += mask[i] * p[i];
  return s;
}

TEST(LimitMasks, MatrixIsTheLoneRingStep) {
  for (const StationaryRing& r : configurations()) {
    SCOPED_TRACE(describe(r));
    const int size = r.valence + 1;
    const std::vector<double> s = stationarySubdivisionMatrix(r);
    for (int j = 0; j < size; ++j) {
      std::vector<Vec3> impulse(size, Vec3(0, 0, 0));
      impulse[j] = Vec3(1, 0, 0);
      const LocalRing next = refineLocalRing(lone(r, impulse), CreaseMethod::kUniform);
      ASSERT_EQ(next.rule, r.rule);
      for (int i = 0; i < size; ++i)
        ASSERT_EQ(s[i * size + j], next.points[i][0]) << "row " << i << " col " << j;
    }
  }
}

TEST(LimitMasks, PositionIsTheLimitOfRefinement) {
  int seed = 1;
  for (const StationaryRing& r : configurations()) {
    SCOPED_TRACE(describe(r));
    const StationaryMasks masks = computeStationaryMasks(r);
    LocalRing ring = lone(r, randomRing(r.valence, seed++));
    const Vec3 limit = applyMask(masks.position, ring.points);
    double sum = 0;
    for (double w : masks.position) sum += w;
    EXPECT_NEAR(sum, 1.0, 1e-13);
    // Every point of the ring converges to the limit (the subdominant
    // eigenvalues are at most 0.7 for valences up to 12).
    for (int step = 0; step < 160; ++step) ring = refineLocalRing(ring, CreaseMethod::kUniform);
    for (const Vec3& p : ring.points) EXPECT_LT((p - limit).norm(), 1e-12);
  }
}

// Refines the ring's offsets from its limit, rescaled every step so that
// they stay representable, and returns them: their shape is the one the
// surface takes at the vertex. Rounding leaves a constant offset of 1e-16
// that refinement keeps while the rest shrinks, so each step takes the
// limit out again (with the position mask, checked above).
std::vector<Vec3> flattenedRing(const StationaryRing& r, const std::vector<double>& position,
                                const std::vector<Vec3>& points, int steps) {
  LocalRing ring = lone(r, points);
  for (int step = 0; step < steps; ++step) {
    const Vec3 limit = applyMask(position, ring.points);
    for (Vec3& p : ring.points) p -= limit;
    ring = refineLocalRing(ring, CreaseMethod::kUniform);
    double scale = 0;
    for (const Vec3& p : ring.points) scale = std::max(scale, p.norm());
    for (Vec3& p : ring.points) p *= 1.0 / scale;
  }
  return ring.points;
}

TEST(LimitMasks, TangentPlaneIsWhereTheRefinedRingFlattens) {
  int seed = 100, planes = 0;
  for (const StationaryRing& r : configurations()) {
    SCOPED_TRACE(describe(r));
    const StationaryMasks masks = computeStationaryMasks(r);
    const std::vector<Vec3> points = randomRing(r.valence, seed++);
    const std::vector<Vec3> d = flattenedRing(r, masks.position, points, 400);
    const int n = r.valence;
    for (const SectorMasks& sector : masks.sectors) {
      if (sector.kind != SectorMasks::Kind::kTangentPlane) continue;
      SCOPED_TRACE("sector from " + std::to_string(sector.firstEdge) + ", " +
                   std::to_string(sector.faceCount) + " faces");
      const Vec3 normal =
          (applyMask(sector.tangent1, points) % applyMask(sector.tangent2, points)).normalized();
      // The sector's points: centre and ring firstEdge .. firstEdge+faceCount.
      std::vector<int> idx{0};
      const int last = sector.faceCount == n && !r.boundary ? n - 1 : sector.faceCount;
      for (int k = 0; k <= last; ++k) idx.push_back(1 + (sector.firstEdge + k) % n);
      double worst = 0;
      for (int i : idx) {
        if (d[i].norm() > 1e-3) worst = std::max(worst, std::abs(dot(normal, d[i])) / d[i].norm());
      }
      EXPECT_LT(worst, 1e-8) << "refined ring leaves the plane";
      // Orientation: the sector's faces (centre, k, k+1) turn about +normal.
      // Read after fewer steps: where the two tangents' eigenvalues differ,
      // the faces thin towards a segment and their area underflows.
      const std::vector<Vec3> e = flattenedRing(r, masks.position, points, 40);
      double turn = 0;
      for (int k = 0; k < sector.faceCount; ++k) {
        const Vec3& a = e[1 + (sector.firstEdge + k) % n];
        const Vec3& b = e[1 + (sector.firstEdge + k + 1) % n];
        turn += dot((a - e[0]) % (b - e[0]), normal);
      }
      EXPECT_GT(turn, 0) << "normal points to the back of the faces";
      ++planes;
    }
  }
  EXPECT_GT(planes, 140);
}

// Which sectors have no tangent plane, from the closed-form eigenvalues.
TEST(LimitMasks, SectorsWithoutTangentPlaneAreTheOnesTheoryPredicts) {
  using Kind = SectorMasks::Kind;
  for (int k = 1; k <= 10; ++k) {
    // A boundary crease with k faces: interior eigenvalues 3/8 + cos(j pi/k)/4;
    // the crease curve's tangent (1/2) must be one of the two leading ones,
    // and the next must not tie with it: k <= 5.
    StationaryRing crease{k + 1, true, VertexRule::kCrease, std::vector<bool>(k + 1, false)};
    crease.sharpEdges[0] = crease.sharpEdges[k] = true;
    const StationaryMasks c = computeStationaryMasks(crease);
    ASSERT_EQ(c.sectors.size(), 1u);
    EXPECT_EQ(c.sectors[0].kind, k <= 5 ? Kind::kTangentPlane : Kind::kDominantAndCrease) << "crease, " << k;
    const double interior1 = 0.375 + 0.25 * std::cos(std::numbers::pi / k);
    if (k >= 4 && k <= 5) {
      EXPECT_NEAR(c.sectors[0].lambda1, interior1, 1e-12);
      EXPECT_NEAR(c.sectors[0].lambda2, 0.5, 1e-12);
    }
    // A boundary corner with k faces: the two curve tangents (1/2, 1/2) lead
    // only while the interior's largest, 3/8 + cos(pi/k)/4, is below 1/2.
    StationaryRing corner = crease;
    corner.rule = VertexRule::kCorner;
    const StationaryMasks q = computeStationaryMasks(corner);
    EXPECT_EQ(q.sectors[0].kind, k <= 2 ? Kind::kTangentPlane : Kind::kBoundingCurves) << "corner, " << k;
  }
  for (int n = 3; n <= 12; ++n) {
    // A cusp: its ring's radial mode 3/8 + 1/4 = 5/8 leads alone, a cone.
    StationaryRing cusp{n, false, VertexRule::kCorner, std::vector<bool>(n, false)};
    const StationaryMasks m = computeStationaryMasks(cusp);
    EXPECT_EQ(m.sectors[0].kind, Kind::kConeAxis) << n;
    EXPECT_NEAR(m.sectors[0].lambda1, 0.625, 1e-12);
  }
}

// Where OpenSubdiv's masks are exact (smooth vertices; crease sectors of up
// to three faces), the eigenvector masks give the same normals.
TEST(LimitMasks, SmoothMasksAreTheClosedForm) {
  for (int n = 3; n <= 12; ++n) {
    StationaryRing r{n, false, VertexRule::kSmooth, std::vector<bool>(n, false)};
    const StationaryMasks m = computeStationaryMasks(r);
    const double c = 0.375 + 0.25 * std::cos(2.0 * std::numbers::pi / n);
    const double beta = (0.625 - c * c) / n;
    const double w = 1.0 / (n + 3.0 / (8.0 * beta));
    EXPECT_NEAR(m.position[0], 1.0 - n * w, 1e-13) << n;
    for (int k = 0; k < n; ++k) EXPECT_NEAR(m.position[1 + k], w, 1e-13) << n;
    EXPECT_NEAR(m.sectors[0].lambda1, c, 1e-12);
  }
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// The process-wide cache stops growing at kStationaryMasksCacheEntries:
// past it, new configurations are answered (the same masks) but not kept,
// and what it holds stays. Corners of valence 15 with every set of two or
// more sharp edges give more than enough distinct configurations.
TEST(LimitMasks, TheProcessCacheIsBounded) {
  const int n = 15;
  auto corner = [&](uint32_t bits) {
    StationaryRing ring{n, false, VertexRule::kCorner, std::vector<bool>(n)};
    for (int k = 0; k < n; ++k) ring.sharpEdges[k] = ((bits >> k) & 1u) != 0;
    return ring;
  };
  bool cached = false;
  const StationaryRing first = corner(0b11);
  ASSERT_NE(stationaryMasks(first, &cached), nullptr);
  const bool firstKept = cached;
  size_t asked = 0;
  uint32_t refusedBits = 0;
  for (uint32_t bits = 4; bits < (1u << n) && asked <= kStationaryMasksCacheEntries; ++bits) {
    if (std::popcount(bits) < 2) continue;
    ++asked;
    auto masks = stationaryMasks(corner(bits), &cached);
    ASSERT_NE(masks, nullptr);
    if (!cached) {
      refusedBits = bits;
      EXPECT_EQ(masks->position, computeStationaryMasks(corner(bits)).position)
          << "an answer not kept is still right";
      break;
    }
  }
  EXPECT_NE(refusedBits, 0u) << "the cache took " << asked << " new configurations without refusing one";
  stationaryMasks(first, &cached);
  EXPECT_EQ(cached, firstKept) << "what the cache held before it filled is still there";
  stationaryMasks(corner(refusedBits), &cached);
  EXPECT_FALSE(cached) << "a configuration refused once is not kept later";
}

}  // namespace
}  // namespace tessera
