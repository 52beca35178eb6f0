// The composed lone-ring steps (core/loop/decay_matrix.h) against their
// definition: refining the ring step by step until it is stationary
// (refineLocalRing, itself checked against whole-mesh refinement in
// local_ring_test.cc). For every vertex with semi-sharp features left, on
// meshes with random tags, uniform and Chaikin decay: the matrix applied to
// the ring's points gives the refined ring's points and centre weights, and
// the same stationary rule, boundary and sharp edges; and the stationary
// masks composed with it (limit_masks.h) weigh the level's ring as the
// stationary masks weigh the stationary ring.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "core/loop/decay_matrix.h"
#include "core/loop/level_builder.h"
#include "core/loop/loop_refiner.h"
#include "core/mesh/sharpness.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

using testing::TestMesh;

Vec3 weigh(const std::vector<double>& mask, const std::vector<Vec3>& points) {
  Vec3 sum(0, 0, 0);
  for (size_t i = 0; i < mask.size(); ++i) sum += mask[i] * points[i];
  return sum;
}

LocalRing refinedUntilStationary(LocalRing ring, CreaseMethod method, int& steps) {
  steps = 0;
  while (!ring.isStationary()) {
    ring = refineLocalRing(ring, method);
    ++steps;
  }
  return ring;
}

void checkAgainstSteps(const TestMesh& mesh, CreaseMethod method) {
  SCOPED_TRACE(mesh.name);
  LoopOptions options;
  options.creaseMethod = method;
  auto refiner = LoopRefiner::create(mesh.topology, options, {.levels = 2});
  ASSERT_TRUE(refiner.isOk()) << refiner.status().toString();
  const auto points = refiner->refinePointsPerLevel(mesh.points);
  int checked = 0, maxSteps = 0;
  for (int l = 0; l <= refiner->maxLevel(); ++l) {
    const Level& level = refiner->level(l);
    for (Index v = 0; v < level.numVertices; ++v) {
      const LocalRing ring = gatherLocalRing(level, v, points[l], method);
      if (ring.isStationary()) continue;
      int steps = 0;
      const LocalRing expected = refinedUntilStationary(ring, method, steps);
      const DecayMatrix decay = computeDecayMatrix(ring, method);
      ASSERT_EQ(decay.steps, steps);
      ASSERT_EQ(decay.rule, expected.rule) << "level " << l << " vertex " << v;
      ASSERT_EQ(decay.boundary, expected.boundary);
      std::vector<Vec3> applied;
      decay.apply(ring.points, applied);
      double scale = 0.0;
      for (const Vec3& p : ring.points) scale = std::max(scale, p.norm());
      for (int i = 0; i <= ring.valence; ++i) {
        ASSERT_LE((applied[i] - expected.points[i]).norm(), 1e-13 * std::max(scale, 1.0))
            << "level " << l << " vertex " << v << " point " << i;
        ASSERT_NEAR(decay.weights[static_cast<size_t>(i) * (ring.valence + 1)], expected.centreWeight[i],
                    1e-14);
      }
      for (int k = 0; k < ring.valence; ++k)
        ASSERT_EQ(decay.sharpEdges[k], isSharp(expected.edgeSharpness[k]));
      // The composed masks on the level's ring give what the stationary
      // masks give on the stationary ring.
      const StationaryMasks stationary =
          computeStationaryMasks({ring.valence, expected.boundary, expected.rule, decay.sharpEdges});
      ASSERT_EQ(decay.composed.sectors.size(), stationary.sectors.size());
      ASSERT_LE(
          (weigh(decay.composed.position, ring.points) - weigh(stationary.position, expected.points)).norm(),
          1e-13 * std::max(scale, 1.0));
      bool linear = true;
      for (size_t i = 0; i < stationary.sectors.size(); ++i) {
        const SectorMasks& a = decay.composed.sectors[i];
        const SectorMasks& b = stationary.sectors[i];
        ASSERT_EQ(a.kind, b.kind);
        ASSERT_EQ(a.firstEdge, b.firstEdge);
        ASSERT_EQ(a.faceCount, b.faceCount);
        ASSERT_LE((weigh(a.tangent1, ring.points) - weigh(b.tangent1, expected.points)).norm(),
                  1e-12 * std::max(scale, 1.0));
        ASSERT_LE((weigh(a.tangent2, ring.points) - weigh(b.tangent2, expected.points)).norm(),
                  1e-12 * std::max(scale, 1.0));
        linear = linear && (b.kind == SectorMasks::Kind::kTangentPlane ||
                            b.kind == SectorMasks::Kind::kDominantAndCrease);
      }
      ASSERT_EQ(decay.composedSuffices, linear);
      // The cache answers with the same matrix.
      const DecayMatrix* cached = cachedDecayMatrix(level, v, points[l], method);
      ASSERT_NE(cached, nullptr);
      ASSERT_EQ(cached->weights, decay.weights);
      maxSteps = std::max(maxSteps, steps);
      ++checked;
    }
  }
  EXPECT_GT(checked, 5) << "the tags must leave semi-sharp features to decay";
  EXPECT_GE(maxSteps, 2);
}

TEST(DecayMatrix, ComposesTheLoneRingStepsUniform) {
  checkAgainstSteps(
      testing::withRandomTags(testing::withJitter(testing::doubleTorus(), 0.05, 3), 0.3, 0.1, 31),
      CreaseMethod::kUniform);
  checkAgainstSteps(testing::withRandomTags(testing::openGrid(7, 6), 0.35, 0.1, 32), CreaseMethod::kUniform);
  checkAgainstSteps(testing::withRandomTags(testing::bipyramid(9), 0.4, 0.2, 33), CreaseMethod::kUniform);
}

TEST(DecayMatrix, ComposesTheLoneRingStepsChaikin) {
  checkAgainstSteps(
      testing::withRandomTags(testing::withJitter(testing::doubleTorus(), 0.05, 4), 0.4, 0.1, 41),
      CreaseMethod::kChaikin);
  checkAgainstSteps(testing::withRandomTags(testing::openGrid(7, 6), 0.45, 0.1, 42), CreaseMethod::kChaikin);
  checkAgainstSteps(testing::withRandomTags(testing::diskWithPole(11), 0.5, 0.2, 43), CreaseMethod::kChaikin);
}

// Distinct sharpness values fill the cache; past its bound it answers
// nullptr (the caller refines the ring itself) and keeps what it has.
TEST(DecayMatrix, TheCacheIsBounded) {
  std::thread([] {
    const TestMesh mesh = testing::bipyramid(6);
    const int a = mesh.topology.triangles[0][0], b = mesh.topology.triangles[0][1];
    auto withCrease = [&](float s) {
      BaseTopology topology = mesh.topology;
      topology.creases = {{a, b, s}};
      auto level = buildBaseLevel(topology, LoopOptions{});
      EXPECT_TRUE(level.isOk()) << level.status().toString();
      return std::move(*level);
    };
    auto cached = [&](const Level& level) {
      return cachedDecayMatrix(level, a, mesh.points, CreaseMethod::kUniform);
    };
    const Level first = withCrease(0.25f);
    ASSERT_NE(cached(first), nullptr);
    float s = 0.25f;
    for (size_t i = 1; i < kDecayMatrixCacheEntries; ++i) {
      s = std::nextafter(s, kSharpnessInfinite);
      ASSERT_NE(cached(withCrease(s)), nullptr) << i;
    }
    s = std::nextafter(s, kSharpnessInfinite);
    EXPECT_EQ(cached(withCrease(s)), nullptr);
    EXPECT_NE(cached(first), nullptr);
  }).join();
}

}  // namespace
}  // namespace tessera
