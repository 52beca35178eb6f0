// Morph views on their own (server/document/morph_view.h, docs/PROTOCOL.md
// §14): a view follows the document at its time t, and a rebuild after a key
// changed reports only the regions whose surface hash (docs/PROTOCOL.md
// §6.5) changed, each with its ids inline.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/document/document.h"
#include "core/tessellation/document_grid.h"
#include "server/document/morph_view.h"
#include "support/test_meshes.h"

namespace tessera::server {
namespace {

const LodProfile kProfile{.baseLevel = 1, .maxLevel = 2};

Document cube() {
  auto doc = testing::cubeDocument(2);
  EXPECT_TRUE(doc.isOk()) << doc.status().message();
  return std::move(*doc);
}

// The cube morphing into itself scaled by `scale`.
KeyedDocument growingCube(double scale) {
  KeyedDocument doc(cube());
  std::vector<Vec3> points = doc.key0().basePoints();
  for (Vec3& p : points) p = scale * p;
  EXPECT_TRUE(doc.addKey(points).isOk());
  return doc;
}

// Every region hashed, as its host does when it adds the view.
void hashAll(LodView& view, const QuantizationGrid& grid) {
  for (const auto& [region, mesh] : view.tessellation->regions()) rehashRegion(view, region, grid);
}

TEST(MorphView, AViewFollowsTheDocumentAtItsTime) {
  KeyedDocument doc = growingCube(1.2);
  auto view = buildMorphView(doc, 0.5, kProfile);
  ASSERT_TRUE(view.isOk()) << view.status().message();
  ASSERT_TRUE(view->morphT.has_value());
  EXPECT_EQ(*view->morphT, 0.5);
  ASSERT_NE(view->source, nullptr);
  ASSERT_NE(view->tessellation, nullptr);
  EXPECT_FALSE(view->tessellation->regions().empty());
  EXPECT_EQ(view->tessellation->profile(), kProfile);
  const std::vector<Vec3>& key0 = doc.key0().basePoints();
  const std::vector<Vec3>& at = view->source->basePoints();
  ASSERT_EQ(at.size(), key0.size());
  for (size_t v = 0; v < at.size(); ++v) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(at[v][k], 1.1 * key0[v][k], 1e-12) << "vertex " << v;
  }
}

TEST(MorphView, ADocumentWithOneKeyHasNone) {
  KeyedDocument doc(cube());
  auto view = buildMorphView(doc, 0.5, kProfile);
  ASSERT_FALSE(view.isOk());
  EXPECT_EQ(view.status().code(), ErrorCode::kInvalidArgument);
}

TEST(MorphView, ARebuildReportsOnlyTheRegionsThatChanged) {
  KeyedDocument doc = growingCube(1.2);
  auto grid = documentGrid(doc.key0());
  ASSERT_TRUE(grid.isOk());
  auto view = buildMorphView(doc, 0.5, kProfile);
  ASSERT_TRUE(view.isOk());
  hashAll(*view, *grid);
  const uint64_t hash = view->surfaceHash;
  const size_t regions = view->tessellation->regions().size();

  auto same = rebuildMorphView(doc, *view, *grid);
  ASSERT_TRUE(same.isOk()) << same.status().message();
  EXPECT_TRUE(same->rebuilt);
  EXPECT_TRUE(same->changed.empty()) << "the keys did not change: no region to send";
  EXPECT_TRUE(same->removed.empty());
  EXPECT_EQ(view->surfaceHash, hash);

  // Key 1 changed (the cube grows less): every region moved.
  KeyedDocument changed = growingCube(1.1);
  auto moved = rebuildMorphView(changed, *view, *grid);
  ASSERT_TRUE(moved.isOk()) << moved.status().message();
  EXPECT_TRUE(moved->rebuilt);
  EXPECT_EQ(moved->changed.size(), regions);
  EXPECT_EQ(moved->relaid, moved->changed) << "rebuilt regions carry their ids inline";
  EXPECT_NE(view->surfaceHash, hash);
  EXPECT_NEAR(view->source->basePoints()[0][0], 1.05 * changed.key0().basePoints()[0][0], 1e-12);
}

}  // namespace
}  // namespace tessera::server
