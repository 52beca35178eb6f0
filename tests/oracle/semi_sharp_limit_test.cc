// Catmull-Clark limits at semi-sharp features that have not decayed
// (core/catmark/semi_sharp_limit.h) against their definition: refine the
// whole mesh (the refinement that equals OpenSubdiv Far's,
// catmark_oracle_test.cc) until every feature has decayed, and take the
// limit masks of the vertex there; a vertex keeps its index on every finer
// level. Under uniform decay the vertex's ring alone gives the same limit;
// under Chaikin's it would not (the far ends of its edges decay their halves),
// so it is not taken there.
#include <gtest/gtest.h>

#include <cstdio>

#include "core/catmark/limit.h"
#include "core/catmark/semi_sharp_limit.h"
#include "core/schemes/quad_refiner.h"
#include "support/polygon_meshes.h"

namespace tessera {
namespace {

constexpr int kDeep = 6;  // below every feature's decay: sharpness < 3.8 from level 2

void checkAgainstWholeMesh(const testing::PolyTestMesh& mesh, const CreaseOptions& options) {
  SCOPED_TRACE(mesh.name);
  auto refiner = schemes::QuadRefiner::create(mesh.topology, schemes::QuadScheme::kCatmullClark, options,
                                              {.levels = kDeep});
  ASSERT_TRUE(refiner.isOk()) << refiner.status().toString();
  const auto points = refiner->refinePointsPerLevel(mesh.points);
  const Level& deep = refiner->level(kDeep);
  double worst = 0, worstWeight = 0;
  int checked = 0;
  for (int l = 0; l <= 2; ++l) {
    const Level& level = refiner->level(l);
    for (Index v = 0; v < level.numVertices; ++v) {
      if (!hasUndecayedSemiSharpness(level, v)) continue;
      ASSERT_FALSE(hasUndecayedSemiSharpness(deep, v))
          << "v" << l << ":" << v << " decays below level " << kDeep;
      const auto ring = decayedLimitFrame(level, v, points[l], options);
      ASSERT_TRUE(ring.has_value()) << "v" << l << ":" << v;
      const CatmarkLimitFrame whole = catmarkLimitFrame(deep, v, points[kDeep], options);
      worst = std::max(worst, (ring->position - whole.position).norm());
      // The weight of the vertex's own point: the limit moves by it when
      // the point alone moves.
      std::vector<Vec3> moved = mesh.points;
      if (l == 0 && checked < 8) {  // a whole refinement each
        moved[static_cast<size_t>(v)] += Vec3(1, 0, 0);
        const auto shifted = refiner->refinePointsPerLevel(moved);
        const double weight =
            catmarkLimitFrame(deep, v, shifted[kDeep], options).position[0] - whole.position[0];
        worstWeight = std::max(worstWeight, std::abs(weight - catmarkSelfLimitWeight(level, v, options)));
      }
      ++checked;
    }
  }
  std::printf(
      "  %-24s %d semi-sharp vertices at levels 0-2: limits within %.2e of the whole mesh's, "
      "own weights within %.2e\n",
      mesh.name.c_str(), checked, worst, worstWeight);
  EXPECT_GT(checked, 20);
  EXPECT_LE(worst, 1e-12);
  EXPECT_LE(worstWeight, 1e-12);
}

TEST(SemiSharpLimit, TheRingAloneGivesTheWholeMeshsLimitUnderUniformDecay) {
  for (auto boundary : {BoundaryInterpolation::kEdgeOnly, BoundaryInterpolation::kEdgeAndCorner}) {
    const CreaseOptions options{CreaseMethod::kUniform, boundary};
    checkAgainstWholeMesh(
        testing::withRandomPolyTags(testing::withPolyJitter(testing::quadTorus(8, 6), 0.05, 4), 0.2, 0.1, 40),
        options);
    checkAgainstWholeMesh(
        testing::withRandomPolyTags(testing::withPolyJitter(testing::quadGrid(6, 5), 0.05, 6), 0.3, 0.1, 41),
        options);
  }
}

TEST(SemiSharpLimit, ChaikinsDecayKeepsLimitsMasks) {
  const auto mesh =
      testing::withRandomPolyTags(testing::withPolyJitter(testing::quadTorus(8, 6), 0.05, 4), 0.2, 0.1, 40);
  const CreaseOptions options{CreaseMethod::kChaikin, BoundaryInterpolation::kEdgeOnly};
  auto refiner =
      schemes::QuadRefiner::create(mesh.topology, schemes::QuadScheme::kCatmullClark, options, {.levels = 1});
  ASSERT_TRUE(refiner.isOk());
  int semiSharp = 0;
  for (Index v = 0; v < refiner->level(0).numVertices; ++v) {
    if (!hasUndecayedSemiSharpness(refiner->level(0), v)) continue;
    ++semiSharp;
    EXPECT_FALSE(takesDecayedLimit(refiner->level(0), v, options));
    EXPECT_FALSE(
        decayedLimitFrame(refiner->level(0), v, refiner->refinePointsPerLevel(mesh.points)[0], options));
  }
  EXPECT_GT(semiSharp, 10);
}

}  // namespace
}  // namespace tessera
