// The limit of the vertex one Loop step puts on an edge, read from the
// level itself (core/loop/edge_child_limit.h), against the limit of that
// vertex after a uniform refinement (limit.h, whose exact limits are checked
// against OpenSubdiv in tests/oracle): equal to rounding at every smooth and
// infinitely sharp edge, at levels 0 and 1, on closed and open meshes with
// creases, corners and semi-sharp edges; and no answer at a semi-sharp edge.
#include <gtest/gtest.h>

#include "core/io/mesh_import.h"
#include "core/loop/edge_child_limit.h"
#include "core/loop/limit.h"
#include "core/loop/loop_refiner.h"
#include "core/mesh/sharpness.h"
#include "support/procedural_meshes.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

struct Counted {
  int smooth = 0, sharp = 0, semiSharp = 0;
};

void check(const std::string& name, const BaseTopology& topology, std::span<const Vec3> basePoints,
           Counted& counted) {
  const LoopOptions options;
  auto refiner = LoopRefiner::create(topology, options, {.levels = 2, .fullTopologyInLastLevel = true});
  ASSERT_TRUE(refiner.isOk()) << name << ": " << refiner.status().message();
  const auto points = refiner->refinePointsPerLevel(basePoints);
  for (int l = 0; l < 2; ++l) {
    const Level& level = refiner->level(l);
    const Level& next = refiner->level(l + 1);
    std::vector<Vec3> positions(points[l + 1].size()), normals(points[l + 1].size());
    computeLimit(next, points[l + 1], positions, normals);
    double scale = 0;
    for (const Vec3& p : points[l]) scale = std::max(scale, p.norm());
    EdgeChildLimits limits(level, points[l], options);
    for (Index e = 0; e < level.numEdges(); ++e) {
      const float s = level.edgeSharpness[e];
      const auto got = limits.limit(e);
      if (isSharp(s) && !isInfinite(s)) {
        EXPECT_FALSE(got.has_value())
            << name << " level " << l << " edge " << e << " (sharpness " << s << ")";
        ++counted.semiSharp;
        continue;
      }
      ASSERT_TRUE(got.has_value()) << name << " level " << l << " edge " << e;
      // Uniform numbering (refinement.h): the vertex on edge e follows the
      // children of the level's vertices.
      const Vec3& expected = positions[level.numVertices + e];
      EXPECT_LE((*got - expected).norm(), 1e-12 * scale)
          << name << " level " << l << " edge " << e << " (sharpness " << s << ")";
      ++(isInfinite(s) ? counted.sharp : counted.smooth);
    }
  }
}

TEST(EdgeChildLimit, EqualsTheLimitOfTheRefinedVertexAtSmoothAndSharpEdges) {
  Counted counted;
  for (const testing::TestMesh& mesh :
       {testing::withJitter(testing::torus(8, 6), 0.05, 1),
        testing::withJitter(testing::doubleTorus(), 0.03, 2), testing::openGrid(5, 4),
        testing::diskWithPole(7),
        testing::withRandomTags(testing::withJitter(testing::torus(9, 7), 0.04, 3), 0.2, 0.1, 4),
        testing::withRandomTags(testing::openGrid(6, 5), 0.25, 0.1, 5)}) {
    check(mesh.name, mesh.topology, mesh.points, counted);
  }
  auto cube = testing::creasedCube();
  ASSERT_TRUE(cube.isOk());
  check("creased cube", BaseTopology::fromBaseMesh(*cube), cube->positions(), counted);
  auto fandisk = importMesh(testing::cgalMeshPath("fandisk.off"));
  ASSERT_TRUE(fandisk.isOk());
  check("fandisk", BaseTopology::fromBaseMesh(*fandisk), fandisk->positions(), counted);
  std::printf("[ measured ] %d smooth, %d infinitely sharp, %d semi-sharp edges\n", counted.smooth,
              counted.sharp, counted.semiSharp);
  EXPECT_GT(counted.sharp, 100);
  EXPECT_GT(counted.semiSharp, 20);
}

}  // namespace
}  // namespace tessera
