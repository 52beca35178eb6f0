// What a profile displays is a function of the document (base mesh, tags,
// active edits) and the profile, never of how the hierarchy grew: a
// document edited step by step with tessellations of two profiles kept up
// to date, an undo and a redo, a removal and a retraction, shows exactly -- bit for bit -- what a fresh
// document given the same edit list shows (bit-identical replay of a
// journal, tessellation.h).
#include <gtest/gtest.h>

#include <array>

#include <random>
#include <string>
#include <vector>

#include "core/document/document.h"
#include "core/document/document_file.h"
#include "core/io/mesh_import.h"
#include "core/tessellation/tessellation.h"
#include "support/procedural_meshes.h"
#include "support/region_checks.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using testing::expectSameRegions;
using testing::TestMesh;

// The profile compared, and a finer one whose tessellation grows the
// hierarchy deeper than the first needs.
const LodProfile kCoarse{.baseLevel = 1, .maxLevel = 3, .angleThresholdDegrees = 10};
const LodProfile kFine{.baseLevel = 1, .maxLevel = 4, .angleThresholdDegrees = 10};

// One random edit: mostly moves at levels 1..3 (plain and to a limit
// position), sometimes a semi-sharp or sharp crease at level 1 or 2 or a
// vertex sharpness, or an interpolating vertex. Returns false when the document refused it (a crease on
// the boundary), which is fine.
bool randomEdit(Document& doc, std::mt19937& rng) {
  auto pick = [&](uint64_t n) { return std::uniform_int_distribution<uint64_t>(0, n - 1)(rng); };
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const int op = static_cast<int>(pick(12));
  if (op >= 10) {
    // An interpolating vertex (refused where it cannot be).
    const int level = 1 + static_cast<int>(pick(2));
    const VertexId v(level, pick(doc.counts().vertices(level)));
    return doc.setInterpolation(v, pick(4) != 0, std::array<double, 3>{0.5, 1.0, 3.0}[pick(3)]).isOk();
  }
  if (op < 7) {
    const int level = 1 + static_cast<int>(pick(3));
    const VertexId v(level, pick(doc.counts().vertices(level)));
    const Vec3 d(uniform(-.05, .05), uniform(-.05, .05), uniform(-.05, .05));
    if (op < 5) return doc.moveBy(std::span(&v, 1), d).isOk();
    const SparseHierarchy& h = doc.hierarchy();
    Vec3 target = d;
    if (v.level() < h.numLevels()) {
      const Index local = h.level(v.level()).findVertex(v.index());
      if (local >= 0 && h.level(v.level()).isComplete(local)) target += h.limitPosition(v.level(), local);
    }
    return doc.moveToLimit(std::span(&v, 1), target).isOk();
  }
  const int level = 1 + static_cast<int>(pick(2));
  if (op < 9) {
    const float sharpness = pick(3) == 0 ? kSharpnessInfinite : (pick(2) ? 1.5f : 2.0f);
    return doc.setEdgeSharpness(EdgeId(level, pick(doc.counts().edges(level))), sharpness).isOk();
  }
  return doc.setVertexSharpness(VertexId(level, pick(doc.counts().vertices(level))), pick(2) ? 1.0f : 0.0f)
      .isOk();
}

void expectHistoryIndependent(Expected<Document> created, const std::string& name, uint32_t seed) {
  SCOPED_TRACE(name);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  Document& a = *created;
  // History A: edits one by one, each followed by an update of the coarse
  // tessellation; halfway a finer profile is built (and then kept up to
  // date too), and one edit is undone and redone.
  auto coarse = Tessellation::build(a, kCoarse);
  ASSERT_TRUE(coarse.isOk()) << coarse.status().message();
  std::optional<Tessellation> fine;
  std::optional<Edit> removed;
  std::mt19937 rng(seed);
  constexpr int kEdits = 14;
  auto updateAll = [&](const std::string& when) {
    auto changes = coarse->update(a);
    ASSERT_TRUE(changes.isOk()) << when << ": " << changes.status().message();
    if (fine) {
      auto fineChanges = fine->update(a);
      ASSERT_TRUE(fineChanges.isOk()) << when << ": " << fineChanges.status().message();
    }
  };
  for (int i = 0; i < kEdits; ++i) {
    if (!randomEdit(a, rng)) continue;
    updateAll("edit " + std::to_string(i));
    if (::testing::Test::HasFatalFailure()) return;
    if (i == kEdits / 2) {
      auto built = Tessellation::build(a, kFine);
      ASSERT_TRUE(built.isOk()) << built.status().message();
      fine.emplace(std::move(*built));
      const EditId undone = a.edits()[a.edits().size() / 2].id;
      ASSERT_TRUE(a.undo(undone).isOk());
      updateAll("undo");
      ASSERT_TRUE(a.redo(undone).isOk());
      updateAll("redo");
      if (::testing::Test::HasFatalFailure()) return;
    }
    if (i == kEdits * 3 / 4) {
      // An edit removed for good and one retracted (a server takes back an
      // edit it applied, then refused): gone from the document, so gone
      // from what it shows.
      removed = a.edits()[a.edits().size() / 3];
      ASSERT_TRUE(a.remove(removed->id).isOk());
      updateAll("remove");
      if (randomEdit(a, rng)) {
        updateAll("edit to retract");
        ASSERT_TRUE(a.retractLast().isOk());
        updateAll("retract");
      }
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  ASSERT_GE(a.edits().size(), 7u);

  // Document B: the same edit list through the file format, tessellated
  // once.
  auto b = deserializeDocument(serializeDocument(a), name);
  ASSERT_TRUE(b.isOk()) << b.status().message();
  auto coarseB = Tessellation::build(*b, kCoarse);
  ASSERT_TRUE(coarseB.isOk()) << coarseB.status().message();
  expectSameRegions(*coarse, *coarseB, "updated A vs a fresh document");
  if (::testing::Test::HasFatalFailure()) return;

  // Document C: the edits replayed one by one into a fresh document with no
  // tessellation in between, then the fine profile before the coarse one.
  auto c = Document::create(a.baseTopology(), a.basePoints(), a.options());
  ASSERT_TRUE(c.isOk()) << c.status().message();
  // (The removed edit goes in at its place and is removed at the end.)
  bool removedIn = false;
  for (const Edit& edit : a.edits()) {
    if (removed && !removedIn && removed->id.value < edit.id.value) {
      ASSERT_TRUE(c->replay(*removed).isOk());
      removedIn = true;
    }
    ASSERT_TRUE(c->replay(edit).isOk()) << edit.id.toString();
  }
  if (removed) {
    if (!removedIn) {
      ASSERT_TRUE(c->replay(*removed).isOk());
    }
    ASSERT_TRUE(c->remove(removed->id).isOk());
  }
  auto fineC = Tessellation::build(*c, kFine);
  ASSERT_TRUE(fineC.isOk()) << fineC.status().message();
  auto coarseC = Tessellation::build(*c, kCoarse);
  ASSERT_TRUE(coarseC.isOk()) << coarseC.status().message();
  expectSameRegions(*fine, *fineC, "fine: updated A vs replayed C");
  expectSameRegions(*coarse, *coarseC, "coarse: updated A vs replayed C after the fine profile");

  // And A itself, tessellated afresh after all that growth.
  auto again = Tessellation::build(a, kCoarse);
  ASSERT_TRUE(again.isOk()) << again.status().message();
  expectSameRegions(*again, *coarseB, "a fresh build on A vs a fresh document");
}

TEST(TessellationHistory, TheCreasedCubeShowsTheSameRegionsWhateverTheHistory) {
  auto mesh = testing::creasedCube();
  ASSERT_TRUE(mesh.isOk()) << mesh.status().message();
  for (uint32_t seed : {1u, 2u, 3u}) {
    expectHistoryIndependent(Document::create(*mesh, {.maxLevel = 5}), "cube seed " + std::to_string(seed),
                             seed);
    if (HasFatalFailure()) return;
  }
}

TEST(TessellationHistory, SemiSharpCreasesShowTheSameRegionsWhateverTheHistory) {
  const TestMesh mesh = testing::withRandomTags(testing::torus(8, 6), 0.15, 0.05, 3);
  for (uint32_t seed : {4u, 5u, 6u}) {
    expectHistoryIndependent(Document::create(mesh.topology, mesh.points, {.maxLevel = 5}),
                             mesh.name + " seed " + std::to_string(seed), seed);
    if (HasFatalFailure()) return;
  }
}

TEST(TessellationHistory, ASmoothClosedMeshShowsTheSameRegionsWhateverTheHistory) {
  const TestMesh mesh = testing::withJitter(testing::bipyramid(7), 0.05, 2);
  for (uint32_t seed : {7u, 8u, 9u}) {
    expectHistoryIndependent(Document::create(mesh.topology, mesh.points, {.maxLevel = 5}),
                             mesh.name + " seed " + std::to_string(seed), seed);
    if (HasFatalFailure()) return;
  }
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// One random move: a cube control vertex of level 0, 1 or 2 moved by up to
// 0.01 per axis. (The durability test's editors mean to send these, but
// compute the offset in unsigned arithmetic, so that a negative component
// becomes about 1.8e16 and the server refuses the move.)
struct CubeMove {
  VertexId vertex;
  Vec3 displacement;
};
CubeMove randomCubeMove(std::mt19937& rng) {
  const int level = static_cast<int>(rng() % 3);
  const VertexId v(level, rng() % (level == 0 ? 8 : level == 1 ? 26 : 98));
  const Vec3 d(((rng() % 21) - 10.0) * 1e-3, ((rng() % 21) - 10.0) * 1e-3, ((rng() % 21) - 10.0) * 1e-3);
  return {v, d};
}

// Recovery as the server does it: the snapshot, then the journal after it
// (the edits of `current` past the snapshot's last).
Expected<Document> recover(const std::string& snapshot, const Document& current) {
  TESSERA_ASSIGN_OR_RETURN(Document back, deserializeDocument(snapshot, "snapshot"));
  const uint64_t last = back.edits().back().id.value;
  for (const Edit& edit : current.edits()) {
    if (edit.id.value > last) TESSERA_RETURN_IF_ERROR(back.replay(edit));
  }
  return back;
}

// What the durability test checks after a kill -9: a document edited by
// hundreds of moves (a replica, edited incrementally), the same document
// read from a snapshot taken halfway plus the journal after it (a server's
// recovery), and the whole list read at once show the same regions.
TEST(TessellationHistory, ManyMovesMatchASnapshotPlusJournalRecovery) {
  auto mesh = importMesh(testing::sourceTestDataPath("cube.obj"));
  ASSERT_TRUE(mesh.isOk());
  auto replica = Document::create(*mesh, {.maxLevel = 4});
  ASSERT_TRUE(replica.isOk());
  const LodProfile profile{.baseLevel = 1, .maxLevel = 3, .angleThresholdDegrees = 15};
  std::mt19937 local(20261122);
  std::string snapshot;
  constexpr int kMoves = 600;
  for (int i = 0; i < kMoves; ++i) {
    const CubeMove m = randomCubeMove(local);
    ASSERT_TRUE(replica->moveBy(std::span(&m.vertex, 1), m.displacement).isOk());
    if (i == kMoves / 2) snapshot = serializeDocument(*replica);
  }
  auto recovered = recover(snapshot, *replica);
  ASSERT_TRUE(recovered.isOk()) << recovered.status().message();
  auto whole = deserializeDocument(serializeDocument(*replica), "whole");
  ASSERT_TRUE(whole.isOk());
  auto a = Tessellation::build(*replica, profile);
  auto b = Tessellation::build(*recovered, profile);
  auto c = Tessellation::build(*whole, profile);
  ASSERT_TRUE(a.isOk() && b.isOk() && c.isOk());
  expectSameRegions(*a, *c, "incremental replica vs the whole list");
  expectSameRegions(*b, *c, "snapshot plus journal vs the whole list");
}

// A command resolves to the same stored offsets whatever the document's
// history: a server that reloaded from a snapshot must turn a client's world
// displacement into the very offsets a replica that never reloaded stores
// (the durability test's replay depends on it).
TEST(TessellationHistory, MovesResolveToTheSameOffsetsAfterAReload) {
  auto mesh = importMesh(testing::sourceTestDataPath("cube.obj"));
  ASSERT_TRUE(mesh.isOk());
  auto replica = Document::create(*mesh, {.maxLevel = 4});
  auto reloaded = Document::create(*mesh, {.maxLevel = 4});
  ASSERT_TRUE(replica.isOk() && reloaded.isOk());
  std::mt19937 local(20261123);
  std::string snapshot;
  std::optional<Tessellation> view;
  for (int i = 0; i < 600; ++i) {
    const CubeMove m = randomCubeMove(local);
    ASSERT_TRUE(replica->moveBy(std::span(&m.vertex, 1), m.displacement).isOk());
    ASSERT_TRUE(reloaded->moveBy(std::span(&m.vertex, 1), m.displacement).isOk());
    const auto& a = std::get<MoveEdit>(replica->edits().back().change).offsets[0].localOffset;
    const auto& b = std::get<MoveEdit>(reloaded->edits().back().change).offsets[0].localOffset;
    ASSERT_TRUE(a[0] == b[0] && a[1] == b[1] && a[2] == b[2])
        << "move " << i << " of " << m.vertex.toString() << ": " << a[0] - b[0] << " " << a[1] - b[1] << " "
        << a[2] - b[2];
    if (view) {
      ASSERT_TRUE(view->update(*reloaded).isOk());
    }
    if (i % 7 == 6) snapshot = serializeDocument(*reloaded);
    if (i % 29 == 28) {
      auto back = recover(snapshot, *reloaded);
      ASSERT_TRUE(back.isOk()) << back.status().message();
      *reloaded = std::move(*back);
      // A subscriber's tessellation grows the hierarchy and follows the edits.
      auto built =
          Tessellation::build(*reloaded, {.baseLevel = 1, .maxLevel = 3, .angleThresholdDegrees = 15});
      ASSERT_TRUE(built.isOk());
      view = std::move(*built);
    }
  }
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// An interpolating vertex on the creased cube as the service runs it (profile 1..4, a
// level-1 vertex lifted, made interpolating, undone and redone): the
// tessellation kept up to date shows what a fresh one shows.
TEST(TessellationHistory, AnInterpolatingVertexShowsTheSameRegionsWhateverTheHistory) {
  auto mesh = testing::creasedCube();
  ASSERT_TRUE(mesh.isOk());
  auto doc = Document::create(*mesh, {.maxLevel = 4});
  ASSERT_TRUE(doc.isOk());
  const LodProfile profile{.baseLevel = 1, .maxLevel = 4, .angleThresholdDegrees = 15};
  auto shown = Tessellation::build(*doc, profile);
  ASSERT_TRUE(shown.isOk());
  int tagged = 0;
  for (uint64_t index = 8; index < doc->counts().vertices(1); ++index) {
    const VertexId v(1, index);
    if (!doc->moveBy(std::span(&v, 1), Vec3(0.15, -0.1, 0.2)).isOk()) continue;
    ASSERT_TRUE(shown->update(*doc).isOk());
    auto tag = doc->setInterpolation(v, true, 2.0);
    if (!tag.isOk()) continue;
    ++tagged;
    ASSERT_TRUE(shown->update(*doc).isOk());
    auto fresh = Tessellation::build(*doc, profile);
    expectSameRegions(*shown, *fresh, "tagged " + v.toString());
    ASSERT_TRUE(doc->undo(*tag).isOk());
    ASSERT_TRUE(shown->update(*doc).isOk());
    ASSERT_TRUE(doc->redo(*tag).isOk());
    ASSERT_TRUE(shown->update(*doc).isOk());
    fresh = Tessellation::build(*doc, profile);
    expectSameRegions(*shown, *fresh, "undone and redone " + v.toString());
    auto reloaded = deserializeDocument(serializeDocument(*doc), "cube");
    ASSERT_TRUE(reloaded.isOk());
    expectSameRegions(*shown, *Tessellation::build(*reloaded, profile), "reloaded " + v.toString());
    if (HasFailure()) return;
  }
  EXPECT_GT(tagged, 3);
}

}  // namespace
}  // namespace tessera
