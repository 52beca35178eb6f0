// The lone-ring Loop step (core/loop/local_ring.h) against the real thing:
// refineLevel + interpolateLevel of whole meshes with random semi-sharp and
// infinitely sharp tags, uniform and Chaikin decay. For every vertex whose
// ring is complete, refining its ring alone must give exactly the next
// level's centre, ring points, ring sharpness and rule.
#include <gtest/gtest.h>

#include "core/loop/local_ring.h"
#include "core/loop/loop_refiner.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

using testing::TestMesh;

void checkAgainstRefinement(const TestMesh& mesh, CreaseMethod method) {
  SCOPED_TRACE(mesh.name);
  LoopOptions options;
  options.creaseMethod = method;
  auto refiner = LoopRefiner::create(mesh.topology, options, {.levels = 3});
  ASSERT_TRUE(refiner.isOk()) << refiner.status().toString();
  const auto points = refiner->refinePointsPerLevel(mesh.points);
  int checked = 0, semiSharp = 0;
  for (int l = 0; l + 1 <= refiner->maxLevel(); ++l) {
    const Level& level = refiner->level(l);
    const Level& child = refiner->level(l + 1);
    for (Index v = 0; v < level.numVertices; ++v) {
      const LocalRing ring = gatherLocalRing(level, v, points[l], method);
      semiSharp += ring.isStationary() ? 0 : 1;
      const LocalRing next = refineLocalRing(ring, method);
      // Child v keeps v's index and its ring order (refinement.cc).
      ASSERT_EQ(next.rule, child.vertexRules[v]) << "level " << l << " vertex " << v;
      ASSERT_EQ(next.vertexSharpness, child.vertexSharpness[v]);
      ASSERT_EQ(next.points[0], points[l + 1][v]) << "centre, level " << l << " vertex " << v;
      auto ringV = child.ringVerticesOf(v);
      auto ringE = child.ringEdgesOf(v);
      for (int k = 0; k < next.valence; ++k) {
        ASSERT_EQ(next.points[1 + k], points[l + 1][ringV[k]])
            << "level " << l << " vertex " << v << " ring " << k;
        ASSERT_EQ(next.edgeSharpness[k], child.edgeSharpness[ringE[k]]) << "level " << l << " vertex " << v;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(semiSharp, 5) << "the tags must leave semi-sharp features to decay";
}

TEST(LocalRing, OneStepIsTheRefinersStepUniform) {
  checkAgainstRefinement(
      testing::withRandomTags(testing::withJitter(testing::doubleTorus(), 0.05, 3), 0.3, 0.1, 11),
      CreaseMethod::kUniform);
  checkAgainstRefinement(testing::withRandomTags(testing::openGrid(7, 6), 0.35, 0.1, 12),
                         CreaseMethod::kUniform);
  checkAgainstRefinement(testing::withRandomTags(testing::bipyramid(9), 0.4, 0.2, 13),
                         CreaseMethod::kUniform);
}

TEST(LocalRing, OneStepIsTheRefinersStepChaikin) {
  checkAgainstRefinement(
      testing::withRandomTags(testing::withJitter(testing::doubleTorus(), 0.05, 4), 0.4, 0.1, 21),
      CreaseMethod::kChaikin);
  checkAgainstRefinement(testing::withRandomTags(testing::openGrid(7, 6), 0.45, 0.1, 22),
                         CreaseMethod::kChaikin);
  checkAgainstRefinement(testing::withRandomTags(testing::diskWithPole(11), 0.5, 0.2, 23),
                         CreaseMethod::kChaikin);
}

// The centre's weight channel is the derivative of every point, after any
// number of steps, with respect to the original centre's control point:
// check it by moving that point.
TEST(LocalRing, CentreWeightIsTheDerivative) {
  const TestMesh mesh =
      testing::withRandomTags(testing::withJitter(testing::doubleTorus(), 0.05, 5), 0.35, 0.15, 31);
  auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = 1});
  ASSERT_TRUE(refiner.isOk());
  const Level& level = refiner->level(1);
  const auto points = refiner->refinePointsPerLevel(mesh.points)[1];
  int checked = 0;
  for (Index v = 0; v < level.numVertices; v += 7) {
    LocalRing ring = gatherLocalRing(level, v, points, CreaseMethod::kUniform);
    LocalRing moved = ring;
    moved.points[0] += Vec3(0.5, 0, 0);
    for (int step = 0; step < 4; ++step) {
      ring = refineLocalRing(ring, CreaseMethod::kUniform);
      moved = refineLocalRing(moved, CreaseMethod::kUniform);
      for (size_t i = 0; i < ring.points.size(); ++i) {
        const double derivative = (moved.points[i][0] - ring.points[i][0]) / 0.5;
        ASSERT_NEAR(derivative, ring.centreWeight[i], 1e-12)
            << "vertex " << v << " step " << step << " point " << i;
      }
    }
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

}  // namespace
}  // namespace tessera
