// Building blocks of hierarchical editing: local frames that follow the
// surface (§2.3, §4.3) and the direct-manipulation solve (§2.2).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/loop/direct_manipulation.h"
#include "core/loop/limit.h"
#include "core/loop/local_frame.h"
#include "core/loop/loop_refiner.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

Vec3 rotate(const Vec3& p, double angle) {  // about the axis (1, 2, 2)/3, then shifted
  const Vec3 k = Vec3(1, 2, 2) / 3.0;
  const double c = std::cos(angle), s = std::sin(angle);
  return c * p + s * (k % p) + (1 - c) * dot(k, p) * k + Vec3(0.3, -1.0, 2.0);
}

TEST(LocalFrame, IsOrthonormalAndRightHanded) {
  for (const auto& mesh : {testing::withJitter(testing::torus(8, 6), 0.05, 4), testing::openGrid(5, 4)}) {
    auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = 2});
    ASSERT_TRUE(refiner.isOk());
    auto points = refiner->refinePoints(mesh.points);
    const Level& level = refiner->finestLevel();
    for (Index v = 0; v < level.numVertices; ++v) {
      LocalFrame f = localFrame(level, v, points);
      EXPECT_NEAR(f.tangent.norm(), 1.0, 1e-12);
      EXPECT_NEAR(f.normal.norm(), 1.0, 1e-12);
      EXPECT_NEAR(dot(f.tangent, f.normal), 0.0, 1e-12);
      EXPECT_NEAR(dot(f.tangent % f.bitangent, f.normal), 1.0, 1e-12);
      const Vec3 w(0.2, -0.7, 1.3);
      EXPECT_NEAR((f.toWorld(f.toLocal(w)) - w).norm(), 0.0, 1e-12);
    }
  }
}

// Detail stored in a local frame rotates with the surface: move the whole
// neighbourhood rigidly and the frame (hence the world offset of any stored
// local detail) turns by the same rotation, not left behind in world axes.
TEST(LocalFrame, FollowsRigidMotionOfTheSurface) {
  auto mesh = testing::withJitter(testing::torus(8, 6), 0.05, 5);
  auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = 2});
  ASSERT_TRUE(refiner.isOk());
  auto points = refiner->refinePoints(mesh.points);
  std::vector<Vec3> moved;
  for (const Vec3& p : points) moved.push_back(rotate(p, 0.9));
  const Level& level = refiner->finestLevel();
  const Vec3 detail(0.01, -0.02, 0.05);  // a local offset: mostly along the normal
  const Vec3 origin = rotate(Vec3(0, 0, 0), 0.9);
  for (Index v = 0; v < level.numVertices; v += 7) {
    const Vec3 before = localFrame(level, v, points).toWorld(detail);
    const Vec3 after = localFrame(level, v, moved).toWorld(detail);
    EXPECT_NEAR((after - (rotate(before, 0.9) - origin)).norm(), 0.0, 1e-12) << "vertex " << v;
  }
}

TEST(DirectManipulation, LimitLandsOnTheTargetAndOnlyTheOneRingMoves) {
  auto mesh = testing::withRandomTags(testing::withRandomFlips(testing::torus(10, 8), 30, 6), 0.15, 0.03, 6);
  auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = 2});
  ASSERT_TRUE(refiner.isOk());
  const Level& level = refiner->finestLevel();
  const auto points = refiner->refinePoints(mesh.points);
  std::vector<Vec3> before(points.size()), normals;
  computeLimit(level, points, before, normals);
  std::mt19937 rng(6);
  int solved = 0;
  for (Index v = 0; v < level.numVertices; v += 37) {
    const Vec3 target = before[v] + Vec3(0.05, -0.02, 0.03) * (1.0 + (rng() % 5));
    auto edited = points;
    edited[v] = solveControlPoint(level, v, points, target, CreaseMethod::kUniform);
    std::vector<Vec3> after(points.size());
    computeLimit(level, edited, after, normals);
    EXPECT_NEAR((after[v] - target).norm(), 0.0, 1e-12) << "vertex " << v;
    for (Index u = 0; u < level.numVertices; ++u) {
      if (u == v) continue;
      bool neighbour = false;
      for (Index w : level.ringVerticesOf(v)) neighbour = neighbour || w == u;
      if (!neighbour) {
        EXPECT_EQ(after[u], before[u]) << "vertex " << u << " moved by editing " << v;
      }
    }
    ++solved;
  }
  EXPECT_GT(solved, 10);
}

}  // namespace
}  // namespace tessera
