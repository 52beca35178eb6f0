// The explicit comparison with OpenSubdiv's PrimvarRefiner::Limit()
// (docs/LIMITS.md "How it is checked"): per kind of vertex and level, how far Limit()
// is from Tessera's exact limit. Limit() applies the masks of the rules at
// the level (semi-sharp counts as infinitely sharp; Hoppe et al.'s crease
// masks; the smooth mask at darts; the first face's plane at corners), so it
// agrees where those are exact and differs elsewhere; in the normal the
// difference does not go away as the level rises, since a dart or a wide
// sector keeps its configuration at every level. The table printed here is
// the one in docs/LIMITS.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "core/loop/limit.h"
#include "core/loop/loop_refiner.h"
#include "oracle/limit_categories.h"
#include "oracle/osd_reference.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

using oracle::LimitCategory;
using testing::TestMesh;

struct Worst {
  double position = 0, normal = 0;
  int count = 0;
};

// worst[category][level]
using Table = std::map<LimitCategory, std::map<int, Worst>>;

void accumulate(const TestMesh& mesh, const LoopOptions& options, int levels, Table& table) {
  auto refiner = LoopRefiner::create(mesh.topology, options, {.levels = levels});
  ASSERT_TRUE(refiner.isOk());
  const auto osd = oracle::refineWithOpenSubdiv(mesh.topology, mesh.points, options, *refiner, true);
  const auto ours = refiner->refinePointsPerLevel(mesh.points);
  Vec3 lo = mesh.points[0], hi = mesh.points[0];
  for (const auto& p : mesh.points) lo.minimize(p), hi.maximize(p);
  const double diagonal = (hi - lo).norm();
  for (int l = 0; l <= levels; ++l) {
    const Level& level = refiner->level(l);
    for (Index v = 0; v < level.numVertices; ++v) {
      const LimitFrame frame = limitFrame(level, v, ours[l], options.creaseMethod);
      Worst& w = table[oracle::categoryOf(level, v)][l];
      w.position = std::max(w.position, (frame.position - osd[l].limitPositions[v]).norm() / diagonal);
      const Vec3 n = osd[l].limitTangent1[v] % osd[l].limitTangent2[v];
      if (n.norm() > 0 && frame.normal().norm() > 0) {
        w.normal = std::max(w.normal, std::atan2((n % frame.normal()).norm(), dot(n, frame.normal())));
      }
      ++w.count;
    }
  }
}

TEST(LimitVsOpenSubdiv, WhereAndByHowMuchLimitDiffers) {
  Table table;
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    accumulate(
        testing::withRandomTags(testing::withJitter(testing::doubleTorus(), 0.03, seed), 0.2, 0.05, seed), {},
        3, table);
    accumulate(testing::withRandomTags(testing::openGrid(7, 6), 0.3, 0.05, 10 + seed), {}, 3, table);
    accumulate(testing::withRandomTags(testing::withJitter(testing::torus(10, 8), 0.05, seed), 0.25, 0.05,
                                       20 + seed),
               {}, 3, table);
  }
  std::printf("  %-20s %7s  %-26s %-26s %-26s %-26s\n", "vertex kind", "count", "level 0 (diag, rad)",
              "level 1", "level 2", "level 3");
  for (const auto& [category, levels] : table) {
    int count = 0;
    for (const auto& [l, w] : levels) count += w.count;
    std::printf("  %-20s %7d ", oracle::nameOf(category).c_str(), count);
    for (const auto& [l, w] : levels) std::printf(" %.1e %.1e            ", w.position, w.normal);
    std::printf("\n");
    const Worst& first = levels.at(0);
    const Worst& last = levels.rbegin()->second;
    if (oracle::osdNormalIsExact(category)) {
      // Float weights in PrimvarRefiner: the tolerances of loop_oracle_test.cc.
      for (const auto& [l, w] : levels) {
        EXPECT_LE(w.position, 1e-5) << oracle::nameOf(category) << " level " << l;
        EXPECT_LE(w.normal, 1e-4) << oracle::nameOf(category) << " level " << l;
      }
    } else {
      // A real difference, at level 0 and still at the last level: a dart
      // or a wide sector keeps its configuration at every level, and so
      // does Limit()'s error in the normal there.
      EXPECT_GT(std::max(first.normal, first.position), 1e-3) << oracle::nameOf(category);
      EXPECT_GT(std::max(last.normal, last.position), 1e-3) << oracle::nameOf(category);
    }
  }
  for (LimitCategory c : {LimitCategory::kSmooth, LimitCategory::kNarrowCrease, LimitCategory::kWideCrease,
                          LimitCategory::kDart, LimitCategory::kSemiSharp}) {
    EXPECT_TRUE(table.count(c)) << "the shapes must contain " << oracle::nameOf(c);
  }
}

}  // namespace
}  // namespace tessera
