// computeLimit's cached stencils (core/loop/limit_stencil.h) against the
// general path they shortcut: exactVertexLimit's frame, itself checked
// against Bfr and against the refined rings (bfr_limit_test.cc,
// limit_masks_test.cc). On meshes with random creases, corners, cusps and
// semi-sharp tags, every non-smooth vertex of levels 0-3 gets the same
// position and normal from both, on the first call (stencils built) and the
// second (stencils found); and a full cache leaves the answers unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "core/loop/exact_limit.h"
#include "core/loop/level_builder.h"
#include "core/loop/limit.h"
#include "core/loop/limit_stencil.h"
#include "core/loop/loop_refiner.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

using testing::TestMesh;

// atan2 keeps small angles exact (acos of a rounded cosine cannot go
// below 1.5e-8).
double angle(const Vec3& a, const Vec3& b) {
  return std::atan2((a % b).norm(), dot(a, b));
}

// Returns how many non-smooth vertices were compared.
int compareWithFrames(const TestMesh& mesh) {
  SCOPED_TRACE(mesh.name);
  auto refiner = LoopRefiner::create(mesh.topology, LoopOptions{}, {.levels = 3});
  EXPECT_TRUE(refiner.isOk()) << refiner.status().toString();
  if (!refiner.isOk()) return 0;
  const auto points = refiner->refinePointsPerLevel(mesh.points);
  int compared = 0;
  for (int l = 0; l <= refiner->maxLevel(); ++l) {
    const Level& level = refiner->level(l);
    std::vector<Vec3> positions(level.numVertices), normals(level.numVertices);
    for (int pass = 0; pass < 2; ++pass) {
      computeLimit(level, points[l], positions, normals);
      for (Index v = 0; v < level.numVertices; ++v) {
        if (level.vertexRules[v] == VertexRule::kSmooth) continue;
        const LimitFrame frame = exactVertexLimit(level, v, points[l], CreaseMethod::kUniform, false).frame;
        EXPECT_LE((positions[v] - frame.position).norm(), 1e-14 * std::max(1.0, frame.position.norm()))
            << "level " << l << " vertex " << v << " pass " << pass;
        const Vec3 expected = frame.normal();
        if (expected.sqrnorm() == 0.0) {
          EXPECT_EQ(normals[v].sqrnorm(), 0.0) << "level " << l << " vertex " << v;
        } else {
          EXPECT_LE(angle(normals[v], expected), 1e-12)
              << "level " << l << " vertex " << v << " pass " << pass;
        }
        compared += pass == 0 ? 1 : 0;
      }
    }
  }
  return compared;
}

TEST(LimitStencil, ComputeLimitEqualsTheGeneralPath) {
  int compared = 0;
  compared += compareWithFrames(
      testing::withRandomTags(testing::withJitter(testing::doubleTorus(), 0.05, 5), 0.3, 0.1, 51));
  compared += compareWithFrames(testing::withRandomTags(testing::openGrid(7, 6), 0.35, 0.1, 52));
  compared += compareWithFrames(testing::withRandomTags(testing::bipyramid(9), 0.4, 0.2, 53));
  compared += compareWithFrames(
      testing::withRandomTags(testing::withRandomFlips(testing::torus(8, 6), 20, 7), 0.3, 0.15, 54));
  EXPECT_GT(compared, 1000);
}

// Past kLimitStencilCacheEntries the cache refuses new keys and computeLimit
// takes the general path: the answers stay the same.
TEST(LimitStencil, AFullCacheChangesNoAnswer) {
  std::thread([] {
    const TestMesh mesh = testing::bipyramid(6);
    const int a = mesh.topology.triangles[0][0], b = mesh.topology.triangles[0][1];
    // The key of vertex a with one crease of sharpness s at edge (a, b).
    auto keyWithCrease = [&](float s) {
      BaseTopology topology = mesh.topology;
      topology.creases = {{a, b, s}};
      auto level = buildBaseLevel(topology, LoopOptions{});
      LimitStencilKey key;
      EXPECT_TRUE(level.isOk() && limitStencilKey(*level, a, key));
      return key;
    };
    LimitStencil unused;
    float s = 0.25f;
    for (size_t i = 0; i < kLimitStencilCacheEntries; ++i, s = std::nextafter(s, 10.0f)) {
      ASSERT_NE(insertLimitStencil(keyWithCrease(s), unused), nullptr) << i;
    }
    const LimitStencilKey key = keyWithCrease(s);
    EXPECT_EQ(findLimitStencil(key), nullptr);
    EXPECT_EQ(insertLimitStencil(key, unused), nullptr);
    EXPECT_GT(compareWithFrames(testing::withRandomTags(testing::withJitter(testing::doubleTorus(), 0.05, 5),
                                                        0.3, 0.1, 51)),
              100);
  }).join();
}

}  // namespace
}  // namespace tessera
