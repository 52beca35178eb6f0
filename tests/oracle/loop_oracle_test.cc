// Tessera's Loop refinement and limit evaluation against OpenSubdiv 3.5 on
// many generated shapes and tag sets. Tolerances:
// positions within 1e-5 of the bounding-box diagonal, normals within 1e-4 rad
// (PrimvarRefiner's weights are float). Limits are compared where Limit() is
// the true limit (limit_categories.h); limit_vs_osd_test.cc lists the rest
// and bfr_limit_test.cc checks them against Bfr.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/io/mesh_import.h"
#include "core/loop/limit.h"
#include "oracle/limit_categories.h"
#include "oracle/osd_reference.h"
#include "support/procedural_meshes.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using testing::TestMesh;

constexpr double kPositionTolerance = 1e-5;  // times the bounding-box diagonal
constexpr double kNormalTolerance = 1e-4;    // radians

double diagonal(const std::vector<Vec3>& points) {
  Vec3 lo = points[0], hi = points[0];
  for (const auto& p : points) {
    lo.minimize(p);
    hi.maximize(p);
  }
  return (hi - lo).norm();
}

double angleBetween(const Vec3& a, const Vec3& b) {
  return std::atan2((a % b).norm(), a | b);
}

struct OracleCase {
  TestMesh mesh;
  LoopOptions options;
  int levels;
};

void checkAgainstOpenSubdiv(const OracleCase& c) {
  SCOPED_TRACE(c.mesh.name);
  auto refiner = LoopRefiner::create(c.mesh.topology, c.options, {.levels = c.levels});
  ASSERT_TRUE(refiner.isOk()) << refiner.status().toString();
  auto reference = oracle::refineWithOpenSubdiv(c.mesh.topology, c.mesh.points, c.options, *refiner, true);
  auto ours = refiner->refinePointsPerLevel(c.mesh.points);
  const double tol = kPositionTolerance * diagonal(c.mesh.points);

  int normalsCompared = 0, normalsSkipped = 0, positionsCompared = 0;
  for (int l = 0; l <= c.levels; ++l) {
    SCOPED_TRACE("level " + std::to_string(l));
    const Level& level = refiner->level(l);
    ASSERT_EQ(static_cast<int>(ours[l].size()), level.numVertices);
    // The first V0 vertices are the images of the input vertices, in order:
    // the vertex map of the oracle is the identity on them by construction,
    // so agreement below also checks this ordering.
    double worstPoint = 0, worstLimit = 0, worstNormal = 0;
    int worstPointVertex = -1, worstLimitVertex = -1, worstNormalVertex = -1;
    for (int v = 0; v < level.numVertices; ++v) {
      double dp = (ours[l][v] - reference[l].points[v]).norm();
      if (dp > worstPoint) worstPoint = dp, worstPointVertex = v;
      LimitFrame frame = limitFrame(level, v, ours[l], c.options.creaseMethod);
      const oracle::LimitCategory category = oracle::categoryOf(level, v);
      if (!oracle::osdPositionIsExact(category)) continue;
      ++positionsCompared;
      double dl = (frame.position - reference[l].limitPositions[v]).norm();
      if (dl > worstLimit) worstLimit = dl, worstLimitVertex = v;
      if (!oracle::osdNormalIsExact(category)) continue;
      const Vec3& t1 = reference[l].limitTangent1[v];
      const Vec3& t2 = reference[l].limitTangent2[v];
      const Vec3 cross = t1 % t2;
      // A normal is defined only where the reference tangents span a plane.
      if (cross.norm() <= 1e-8 * t1.norm() * t2.norm()) {
        ++normalsSkipped;
        continue;
      }
      ++normalsCompared;
      double da = angleBetween(frame.normal(), cross);
      if (da > worstNormal) worstNormal = da, worstNormalVertex = v;
    }
    EXPECT_LE(worstPoint, tol) << "refined point of vertex " << worstPointVertex;
    EXPECT_LE(worstLimit, tol) << "limit position of vertex " << worstLimitVertex << " rule "
                               << int(level.vertexRules[std::max(worstLimitVertex, 0)]);
    EXPECT_LE(worstNormal, kNormalTolerance) << "limit normal of vertex " << worstNormalVertex << " rule "
                                             << int(level.vertexRules[std::max(worstNormalVertex, 0)]);
  }
  // The comparison must not be vacuous.
  EXPECT_GT(positionsCompared, 0);
  EXPECT_GT(normalsCompared, 0);
  EXPECT_LE(normalsSkipped, normalsCompared / 100 + 1);
}

std::vector<OracleCase> smoothShapes() {
  std::vector<OracleCase> cases;
  LoopOptions o;
  cases.push_back({testing::icosahedron(), o, 4});
  cases.push_back({testing::withJitter(testing::torus(10, 8), 0.05, 1), o, 4});
  cases.push_back({testing::openGrid(6, 5), o, 4});
  cases.push_back({testing::diskWithPole(24), o, 4});
  cases.push_back({testing::bipyramid(22), o, 3});
  for (int n = 3; n <= 12; ++n) cases.push_back({testing::withJitter(testing::bipyramid(n), 0.03, n), o, 3});
  cases.push_back({testing::withRandomFlips(testing::torus(12, 10), 60, 7), o, 3});
  cases.push_back({testing::doubleTorus(), o, 3});
  return cases;
}

TEST(LoopOracle, SmoothShapesMatchOpenSubdiv) {
  for (const auto& c : smoothShapes()) checkAgainstOpenSubdiv(c);
}

TEST(LoopOracle, BoundaryEdgeAndCornerMatchesOpenSubdiv) {
  LoopOptions o;
  o.boundary = BoundaryInterpolation::kEdgeAndCorner;
  checkAgainstOpenSubdiv({testing::openGrid(6, 5), o, 4});
  checkAgainstOpenSubdiv({testing::diskWithPole(7), o, 4});
}

TEST(LoopOracle, RandomCreaseSetsMatchOpenSubdiv) {
  int count = 0;
  for (uint32_t seed = 1; seed <= 6; ++seed) {
    for (const TestMesh& base :
         {testing::withRandomFlips(testing::torus(10, 8), 40, seed), testing::openGrid(7, 6),
          testing::bipyramid(5 + seed), testing::doubleTorus()}) {
      for (double fraction : {0.08, 0.25}) {
        LoopOptions o;
        checkAgainstOpenSubdiv({testing::withRandomTags(base, fraction, 0.04, seed * 31 + count), o, 3});
        ++count;
      }
    }
  }
}

TEST(LoopOracle, ChaikinCreasingMatchesOpenSubdiv) {
  for (uint32_t seed = 11; seed <= 16; ++seed) {
    LoopOptions o;
    o.creaseMethod = CreaseMethod::kChaikin;
    checkAgainstOpenSubdiv(
        {testing::withRandomTags(testing::withRandomFlips(testing::torus(10, 8), 40, seed), 0.3, 0.02, seed),
         o, 3});
  }
}

// Named feature configurations: a dart (one sharp edge ends inside), a
// crease loop with semi-sharp values 1, 2 and 2.5, corners and a cusp.
TEST(LoopOracle, NamedFeaturesMatchOpenSubdiv) {
  for (float s : {1.0f, 2.0f, 2.5f, kSharpnessInfinite}) {
    TestMesh m = testing::withJitter(testing::torus(10, 8), 0.02, 3);
    m.name = "crease-loop-" + std::to_string(s);
    for (int i = 0; i < 10; ++i) m.topology.creases.push_back({i * 8, ((i + 1) % 10) * 8, s});
    checkAgainstOpenSubdiv({m, LoopOptions{}, 4});
  }
  TestMesh dart = testing::torus(10, 8);
  dart.name = "dart";
  dart.topology.creases = {{0, 8, kSharpnessInfinite}, {8, 16, kSharpnessInfinite}};
  checkAgainstOpenSubdiv({dart, LoopOptions{}, 4});

  TestMesh corners = testing::icosahedron();
  corners.name = "corner-and-cusp";
  corners.topology.creases = {
      {0, 11, kSharpnessInfinite}, {0, 5, kSharpnessInfinite}, {0, 1, kSharpnessInfinite}};
  corners.topology.vertexSharpness.assign(12, 0.0f);
  corners.topology.vertexSharpness[3] = kSharpnessInfinite;  // cusp: no sharp edge meets it
  corners.topology.vertexSharpness[7] = 1.5f;                // semi-sharp cusp
  checkAgainstOpenSubdiv({corners, LoopOptions{}, 4});
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

TestMesh loadReal(const std::string& name) {
  ImportOptions options;
  options.triangulate = true;
  auto mesh = importMesh(testing::cgalMeshPath(name), options);
  if (!mesh.isOk()) throw std::runtime_error(mesh.status().toString());
  TestMesh m;
  m.name = name;
  m.topology = BaseTopology::fromBaseMesh(*mesh);
  m.points = mesh->positions();
  return m;
}

// Real meshes from Debian's libcgal-demo: fandisk (its feature lines tagged
// at random here), the hand with a valence-20 pole, the genus-3 elephant, the
// mushroom with a boundary, a knot, and a genus-3 quad mesh triangulated.
TEST(LoopOracle, RealMeshesMatchOpenSubdiv) {
  checkAgainstOpenSubdiv({loadReal("hand.off"), LoopOptions{}, 4});
  checkAgainstOpenSubdiv({loadReal("3torus.off"), LoopOptions{}, 4});
  checkAgainstOpenSubdiv({loadReal("mushroom.off"), LoopOptions{}, 3});
  checkAgainstOpenSubdiv({loadReal("elephant.off"), LoopOptions{}, 3});
  checkAgainstOpenSubdiv({loadReal("knot1.off"), LoopOptions{}, 3});
  checkAgainstOpenSubdiv({loadReal("fandisk.off"), LoopOptions{}, 3});
}

TEST(LoopOracle, RealMeshesWithRandomTagsMatchOpenSubdiv) {
  checkAgainstOpenSubdiv(
      {testing::withRandomTags(loadReal("fandisk.off"), 0.05, 0.01, 41), LoopOptions{}, 3});
  checkAgainstOpenSubdiv({testing::withRandomTags(loadReal("hand.off"), 0.1, 0.02, 42), LoopOptions{}, 3});
  LoopOptions chaikinCorners;
  chaikinCorners.creaseMethod = CreaseMethod::kChaikin;
  chaikinCorners.boundary = BoundaryInterpolation::kEdgeAndCorner;
  checkAgainstOpenSubdiv(
      {testing::withRandomTags(loadReal("mushroom.off"), 0.1, 0.02, 43), chaikinCorners, 3});
}

}  // namespace
}  // namespace tessera
