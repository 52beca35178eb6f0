// What SparseHierarchy::create refuses on a polygon base level, with the
// reason: interpolating vertices on Catmull-Clark's split (they are Loop's
// ghost rings, docs/INTERPOLATION.md), and level counts that describe
// another base. OpenSubdiv holds the accepted hierarchies' values
// (tests/oracle/catmark_hierarchy_oracle_test.cc).
#include <gtest/gtest.h>

#include "core/catmark/polygon_level.h"
#include "core/hierarchy/sparse_hierarchy.h"
#include "support/polygon_meshes.h"
#include "support/sparse_levels.h"

namespace tessera {
namespace {

TEST(CatmarkHierarchy, RefusesInterpolatingVerticesNamingTheEdit) {
  const auto cube = testing::quadCube();
  auto level0 = buildPolyLevel(cube.topology, {});
  ASSERT_TRUE(level0.isOk());
  const LevelCounts counts = testing::quadCountsOf(*level0, 3);
  const std::vector<Edit> edits = {{EditId{7}, true, InterpolationEdit{VertexId(1, 2)}}};
  auto h = SparseHierarchy::create(std::move(*level0), cube.points, {}, counts, 1, edits);
  ASSERT_FALSE(h.isOk());
  EXPECT_EQ(h.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(h.status().message().find("edit7 makes v1:2 interpolating"), std::string::npos)
      << h.status().message();
}

TEST(CatmarkHierarchy, RefusesCountsOfAnotherBase) {
  const auto cube = testing::quadCube();
  const auto grid = testing::quadGrid(3, 3);
  auto cubeLevel = buildPolyLevel(cube.topology, {});
  auto gridLevel = buildPolyLevel(grid.topology, {});
  ASSERT_TRUE(cubeLevel.isOk() && gridLevel.isOk());
  const LevelCounts gridCounts = testing::quadCountsOf(*gridLevel, 2);
  auto h = SparseHierarchy::create(std::move(*cubeLevel), cube.points, {}, gridCounts, 1, {});
  ASSERT_FALSE(h.isOk());
  EXPECT_NE(h.status().message().find("disagree"), std::string::npos) << h.status().message();
}

}  // namespace
}  // namespace tessera
