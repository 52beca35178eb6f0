// A tessellation shows semi-sharp creases at their limit: where a profile
// stops refining before the sharpness has decayed, the displayed limit is
// still OpenSubdiv's limit from a level deep enough for the decay, and the
// same whatever the hierarchy held before (tessellation.h).
#include <gtest/gtest.h>

#include <cmath>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"
#include "core/loop/loop_refiner.h"
#include "core/tessellation/tessellation.h"
#include "oracle/osd_reference.h"
#include "support/region_checks.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

constexpr double kPositionTolerance = 1e-5;  // times the bounding-box diagonal, as the oracle suite
constexpr double kNormalTolerance = 1e-4;    // radians

// The creased cube's vertical edges are semi-sharp (2.5) and its bottom rim
// sharp for one level: a profile ending at level 2 displays them before
// they decay (at level 3).
TEST(SemiSharpDisplay, ShowsOpenSubdivsDecayedLimitWhateverTheHistory) {
  auto mesh = importMesh(testing::sourceTestDataPath("cube.obj"));
  ASSERT_TRUE(mesh.isOk());
  ASSERT_TRUE(applyTagFile(testing::sourceTestDataPath("cube.tags"), *mesh).isOk());
  constexpr int kDeep = 6;
  const LodProfile coarse{.baseLevel = 1, .maxLevel = 2, .angleThresholdDegrees = 10};
  const LodProfile fine{.baseLevel = 1, .maxLevel = 5, .angleThresholdDegrees = 10};

  // History A: a fine profile first (the hierarchy held to level 5), then
  // the coarse one. B: the coarse one alone on a fresh document.
  auto a = Document::create(*mesh, {.maxLevel = kDeep});
  ASSERT_TRUE(a.isOk()) << a.status().message();
  ASSERT_TRUE(Tessellation::build(*a, fine).isOk());
  auto shownA = Tessellation::build(*a, coarse);
  ASSERT_TRUE(shownA.isOk()) << shownA.status().message();
  auto b = Document::create(*mesh, {.maxLevel = kDeep});
  ASSERT_TRUE(b.isOk());
  auto shownB = Tessellation::build(*b, coarse);
  ASSERT_TRUE(shownB.isOk()) << shownB.status().message();
  testing::expectSameRegions(*shownA, *shownB, "after a finer profile vs fresh");

  // OpenSubdiv on the same cube, uniformly to a level past every decay.
  const BaseTopology topology = BaseTopology::fromBaseMesh(*mesh);
  auto refiner = LoopRefiner::create(topology, {}, {.levels = kDeep});
  ASSERT_TRUE(refiner.isOk()) << refiner.status().toString();
  const std::vector<Vec3> points = mesh->positions();
  auto reference = oracle::refineWithOpenSubdiv(topology, points, {}, *refiner, true);
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) lo.minimize(p), hi.maximize(p);
  const double tol = kPositionTolerance * (hi - lo).norm();

  // The displayed vertices on a semi-sharp edge of level 2 (by OpenSubdiv
  // semantics' own refinement): the profile's finest level.
  const Level& level2 = refiner->level(2);
  const Level& deep = refiner->level(kDeep);
  int checked = 0, normalsChecked = 0;
  double worstCoarseMask = 0.0;
  for (const auto& [id, region] : shownB->regions()) {
    for (size_t i = 0; i < region.positions.size(); ++i) {
      const Index v = static_cast<Index>(VertexId::fromPacked(region.vertexIds[i]).index());
      if (v >= level2.numVertices) continue;
      bool semiSharp = false;
      for (Index e : level2.ringEdgesOf(v)) semiSharp = semiSharp || isSemiSharp(level2.edgeSharpness[e]);
      if (!semiSharp) continue;
      ++checked;
      const Vec3& truth = reference[kDeep].limitPositions[v];
      EXPECT_LE((region.positions[i] - truth).norm(), tol) << "v" << v;
      // What OpenSubdiv's mask at the profile's level gives instead.
      worstCoarseMask = std::max(worstCoarseMask, (reference[2].limitPositions[v] - truth).norm());
      // Normals where the features have all decayed (a single normal).
      bool smooth = deep.vertexRules[v] == VertexRule::kSmooth;
      if (!smooth) continue;
      const Vec3 n = reference[kDeep].limitTangent1[v] % reference[kDeep].limitTangent2[v];
      const Vec3& shown = region.normals[i];
      EXPECT_LE(std::atan2((shown % n).norm(), shown | n), kNormalTolerance) << "v" << v;
      ++normalsChecked;
    }
  }
  std::printf(
      "%d semi-sharp crease vertices displayed (%d normals); OpenSubdiv's level-2 masks are off by up to "
      "%g\n",
      checked, normalsChecked, worstCoarseMask);
  EXPECT_GE(checked, 8);
  EXPECT_GE(normalsChecked, 4);
  // The check is sharp: the level-2 masks would fail it.
  EXPECT_GT(worstCoarseMask, 10 * tol);
}

}  // namespace
}  // namespace tessera
