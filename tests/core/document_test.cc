// Hierarchical documents: direct manipulation, detail in local frames that
// follows coarse edits, tags at any level with inheritance, undo/redo/remove,
// and rejection of bad commands without any change.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/document/document.h"
#include "core/loop/limit.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

Document makeDocument(const testing::TestMesh& mesh, int maxLevel = 4) {
  auto doc = Document::create(mesh.topology, mesh.points, {.loop = {}, .maxLevel = maxLevel});
  if (!doc.isOk()) throw std::runtime_error(doc.status().toString());
  return std::move(doc).value();
}

std::vector<Vec3> pointsAt(const Document& doc, int level) {
  auto eval = doc.evaluate(level);
  if (!eval.isOk()) throw std::runtime_error(eval.status().toString());
  return (*eval)->points[level];
}

TEST(Document, DirectManipulationPutsTheLimitOnTheTarget) {
  Document doc = makeDocument(testing::withJitter(testing::torus(8, 6), 0.03, 1));
  for (int level : {0, 2, 3}) {
    const VertexId v(level, 5 + level);
    auto before = doc.evaluate(level);
    ASSERT_TRUE(before.isOk());
    const Vec3 start = limitFrame((*before)->levels[level], 5 + level, (*before)->points[level]).position;
    const Vec3 target = start + Vec3(0.02, 0.05, -0.03);
    auto id = doc.moveToLimit(std::vector<VertexId>{v}, target);
    ASSERT_TRUE(id.isOk()) << id.status().toString();
    auto after = doc.evaluate(level);
    const Vec3 reached = limitFrame((*after)->levels[level], 5 + level, (*after)->points[level]).position;
    EXPECT_NEAR((reached - target).norm(), 0.0, 1e-12) << "level " << level;
  }
}

TEST(Document, GroupMoveSolvesForTheFirstAndShiftsTheOthersAlike) {
  Document doc = makeDocument(testing::torus(8, 6));
  const std::vector<VertexId> group = {VertexId(1, 3), VertexId(1, 60), VertexId(1, 61)};
  const auto before = pointsAt(doc, 1);
  auto eval = doc.evaluate(1);
  const Vec3 target = limitFrame((*eval)->levels[1], 3, before).position + Vec3(0, 0, 0.1);
  ASSERT_TRUE(doc.moveToLimit(group, target).isOk());
  const auto after = pointsAt(doc, 1);
  const Vec3 d = after[3] - before[3];
  EXPECT_GT(d.norm(), 0.05);
  EXPECT_NEAR((after[60] - before[60] - d).norm(), 0.0, 1e-12);
  EXPECT_NEAR((after[61] - before[61] - d).norm(), 0.0, 1e-12);
}

// Fine detail is stored in local frames, so when a coarse edit turns the
// region the detail turns with it instead of staying in world axes.
TEST(Document, FineDetailRotatesWithACoarseEdit) {
  const auto mesh = testing::withJitter(testing::torus(8, 6), 0.03, 2);
  Document doc = makeDocument(mesh);
  const VertexId fine(3, 400);
  const auto plain = pointsAt(doc, 3);
  ASSERT_TRUE(doc.moveBy(std::vector<VertexId>{fine}, Vec3(0.0, 0.03, 0.04)).isOk());
  const Vec3 detailBefore = pointsAt(doc, 3)[400] - plain[400];

  // Rotate the whole base mesh by 60 degrees about z with level-0 moves.
  const double c = std::cos(M_PI / 3), s = std::sin(M_PI / 3);
  auto rot = [&](const Vec3& p) { return Vec3(c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]); };
  for (int v = 0; v < mesh.topology.numVertices; ++v) {
    ASSERT_TRUE(
        doc.moveBy(std::vector<VertexId>{VertexId(0, v)}, rot(mesh.points[v]) - mesh.points[v]).isOk());
  }
  // The same rotation without the fine edit, for the plain surface.
  Document plainDoc = makeDocument(mesh);
  for (int v = 0; v < mesh.topology.numVertices; ++v) {
    ASSERT_TRUE(
        plainDoc.moveBy(std::vector<VertexId>{VertexId(0, v)}, rot(mesh.points[v]) - mesh.points[v]).isOk());
  }
  const Vec3 detailAfter = pointsAt(doc, 3)[400] - pointsAt(plainDoc, 3)[400];
  EXPECT_NEAR((detailAfter - rot(detailBefore)).norm(), 0.0, 1e-12);
  // And it is not the unrotated world vector.
  EXPECT_GT((detailAfter - detailBefore).norm(), 0.01);
}

TEST(Document, TagsAtAnyLevelAreInheritedUntilOverridden) {
  Document doc = makeDocument(testing::torus(8, 6));
  // Edge 10 of level 1 made sharp: its halves at level 2 and quarters at 3 are sharp.
  auto sharp = doc.setEdgeSharpness(EdgeId(1, 10), kSharpnessInfinite);
  ASSERT_TRUE(sharp.isOk()) << sharp.status().toString();
  auto eval = doc.evaluate(3);
  ASSERT_TRUE(eval.isOk());
  EXPECT_TRUE(isInfinite((*eval)->levels[2].edgeSharpness[20]));
  EXPECT_TRUE(isInfinite((*eval)->levels[2].edgeSharpness[21]));
  EXPECT_TRUE(isInfinite((*eval)->levels[3].edgeSharpness[40]));
  // A user override at level 2 is inherited further down.
  ASSERT_TRUE(doc.setEdgeSharpness(EdgeId(2, 20), 0.0f).isOk());
  eval = doc.evaluate(3);
  EXPECT_EQ((*eval)->levels[2].edgeSharpness[20], 0.0f);
  EXPECT_EQ((*eval)->levels[3].edgeSharpness[40], 0.0f);
  EXPECT_TRUE(isInfinite((*eval)->levels[3].edgeSharpness[42]));  // the other half keeps it
  // Undo the first tag: everything smooth again.
  ASSERT_TRUE(doc.undo(*sharp).isOk());
  eval = doc.evaluate(3);
  EXPECT_EQ((*eval)->levels[3].edgeSharpness[42], 0.0f);
  // A vertex made a corner at level 2 keeps its limit position at its control point.
  ASSERT_TRUE(doc.setVertexSharpness(VertexId(2, 7), kSharpnessInfinite).isOk());
  eval = doc.evaluate(2);
  EXPECT_EQ((*eval)->levels[2].vertexRules[7], VertexRule::kCorner);
}

TEST(Document, UndoRedoAndRemoveRestoreTheSurfaceExactly) {
  Document doc = makeDocument(testing::openGrid(5, 4));
  const auto original = pointsAt(doc, 3);
  auto a = doc.moveBy(std::vector<VertexId>{VertexId(1, 12)}, Vec3(0, 0, 0.2));
  const Level& base = (*doc.evaluate(0))->levels[0];
  Index interior = 0;
  while (base.isBoundaryEdge(interior)) ++interior;
  auto b = doc.setEdgeSharpness(EdgeId(0, interior), 2.5f);
  ASSERT_TRUE(a.isOk() && b.isOk()) << a.status().toString() << b.status().toString();
  const auto both = pointsAt(doc, 3);
  ASSERT_TRUE(doc.undo(*a).isOk());
  ASSERT_TRUE(doc.undo(*b).isOk());
  EXPECT_EQ(pointsAt(doc, 3), original);
  ASSERT_TRUE(doc.redo(*a).isOk());
  ASSERT_TRUE(doc.redo(*b).isOk());
  EXPECT_EQ(pointsAt(doc, 3), both);
  ASSERT_TRUE(doc.remove(*a).isOk());
  ASSERT_TRUE(doc.remove(*b).isOk());
  EXPECT_EQ(pointsAt(doc, 3), original);
  EXPECT_TRUE(doc.edits().empty());
}

TEST(Document, RandomEditHistoriesEqualTheirActiveEditsReplayed) {
  const auto mesh = testing::withRandomFlips(testing::torus(8, 6), 12, 3);
  std::mt19937 rng(3);
  Document doc = makeDocument(mesh, 3);
  std::vector<EditId> made;
  for (int step = 0; step < 120; ++step) {
    const int level = static_cast<int>(rng() % 4);
    const int choice = static_cast<int>(rng() % 6);
    if (choice <= 2 || made.empty()) {
      const VertexId v(level, rng() % doc.counts().vertices(level));
      auto id = choice == 0 ? doc.moveToLimit(std::vector<VertexId>{v}, Vec3(0.1, 0.2, 0.3))
                            : doc.moveBy(std::vector<VertexId>{v}, Vec3(0.01 * (rng() % 7), 0, -0.02));
      ASSERT_TRUE(id.isOk()) << id.status().toString();
      made.push_back(*id);
    } else if (choice == 3) {
      // Torus: no boundary, every edge may be tagged.
      auto id =
          doc.setEdgeSharpness(EdgeId(level, rng() % doc.counts().edges(level)), float(rng() % 4) * 0.75f);
      ASSERT_TRUE(id.isOk()) << id.status().toString();
      made.push_back(*id);
    } else {
      const EditId id = made[rng() % made.size()];
      const bool active = std::find_if(doc.edits().begin(), doc.edits().end(), [&](const Edit& e) {
                            return e.id == id;
                          })->active;
      ASSERT_TRUE((active ? doc.undo(id) : doc.redo(id)).isOk());
    }
  }
  std::vector<Edit> active;
  for (const Edit& e : doc.edits()) {
    if (e.active) active.push_back(e);
  }
  auto replay =
      Document::restore(doc.baseTopology(), doc.basePoints(), doc.options(), active, doc.nextEditId());
  ASSERT_TRUE(replay.isOk()) << replay.status().toString();
  EXPECT_EQ(pointsAt(doc, 3), pointsAt(*replay, 3));
}

TEST(Document, BadCommandsAreRejectedWithoutChange) {
  Document doc = makeDocument(testing::openGrid(4, 4), 3);
  ASSERT_TRUE(doc.moveBy(std::vector<VertexId>{VertexId(0, 1)}, Vec3(0, 0, 0.1)).isOk());
  const auto before = pointsAt(doc, 3);
  const uint64_t next = doc.nextEditId();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    Status status;
    std::string message;
  };
  std::vector<Case> cases;
  cases.push_back({doc.undo(EditId{99}), "edit99: no such edit"});
  cases.push_back({doc.redo(EditId{1}), "edit1 is not undone"});
  cases.push_back({doc.moveBy(std::vector<VertexId>{VertexId(4, 0)}, Vec3(0, 0, 1)).status(),
                   "above the maximum level 3"});
  cases.push_back({doc.moveToLimit(std::vector<VertexId>{VertexId(1, 3)}, Vec3(nan, 0, 0)).status(),
                   "target position must be finite"});
  cases.push_back({doc.moveBy(std::vector<VertexId>{VertexId(2, 1u << 20)}, Vec3(0, 0, 1)).status(),
                   "v2:1048576: level 2 has"});
  cases.push_back({doc.setEdgeSharpness(EdgeId(1, 40), -1.0f).status(), "sharpness must be >= 0"});
  cases.push_back({doc.setVertexSharpness(VertexId(1, 4), std::nanf("")).status(), "sharpness must be >= 0"});
  cases.push_back({doc.setEdgeSharpness(EdgeId(0, 0), 1.0f).status(), "lies on the boundary"});
  cases.push_back({doc.moveBy(std::vector<VertexId>{VertexId(1, 2), VertexId(2, 2)}, Vec3(0, 0, 1)).status(),
                   "must share a level"});
  cases.push_back({doc.moveBy(std::vector<VertexId>{}, Vec3(0, 0, 1)).status(), "names no vertex"});
  for (const auto& c : cases) {
    EXPECT_FALSE(c.status.isOk()) << c.message;
    EXPECT_NE(c.status.message().find(c.message), std::string::npos) << c.status.message();
  }
  EXPECT_EQ(doc.nextEditId(), next);
  EXPECT_EQ(doc.edits().size(), 1u);
  EXPECT_EQ(pointsAt(doc, 3), before);
}

}  // namespace
}  // namespace tessera
