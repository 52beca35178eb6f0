// Tiles built for their mesh alone and measured later (core/view/
// tile_catalogue.h): a server sends the tiles an edit reached before it
// measures them. Measured later, after other edits that did not reach
// them, and with their mesh released meanwhile, their mesh and bounds
// equal, bit for bit, those of a tile built and measured at once from the
// same document; and a mesh released before its tile was measured is kept
// for measuring, not built twice.
#include <gtest/gtest.h>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/view/tile_catalogue.h"
#include "support/same_tile.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

// Every tile down to level 2, parents first.
std::vector<TileKey> upperTiles(const TileTree& tree) {
  std::vector<TileKey> all = tree.roots();
  for (size_t i = 0; i < all.size(); ++i) {
    if (all[i].level >= 2) continue;
    for (const TileKey& c : tree.children(all[i])) all.push_back(c);
  }
  return all;
}

TEST(TileCatalogue, TilesMeasuredAfterTheirMeshEqualTilesBuiltAtOnce) {
  auto hand = importMesh(testing::cgalMeshPath("hand.off"));
  ASSERT_TRUE(hand.isOk());
  auto doc = Document::create(*hand, {.maxLevel = 3});
  ASSERT_TRUE(doc.isOk());
  TileCatalogue late(*doc);
  const std::vector<TileKey> keys = upperTiles(late.tree());
  ASSERT_GT(keys.size(), 100u);
  // Meshes first: built, not measured.
  for (size_t i = 0; i < keys.size(); ++i) {
    ASSERT_TRUE(late.mesh(keys[i]).isOk()) << keys[i].toString();
    EXPECT_FALSE(late.isBuilt(keys[i])) << keys[i].toString() << ": measured with its mesh";
    if (i % 2 == 0) late.releaseMesh(keys[i]);  // encoded: its mesh may go once measured
  }
  EXPECT_EQ(late.built(), static_cast<int64_t>(keys.size()));
  // An edit between the mesh and the measure: the tiles it reached go.
  const VertexId moved[] = {VertexId(0, 0)};
  ASSERT_TRUE(doc->moveBy(moved, Vec3(0.01, -0.02, 0.015)).isOk());
  const std::vector<TileKey> gone =
      late.forget(TouchedTiles(doc->hierarchy(), late.tree(), doc->lastUpdate().limits));
  ASSERT_FALSE(gone.empty());
  ASSERT_LT(gone.size(), keys.size() / 4) << "the edit should reach few tiles of the hand";

  TileCatalogue fresh(*doc);
  int64_t kept = 0;
  for (size_t i = 0; i < keys.size(); ++i) {
    const TileKey& k = keys[i];
    const bool forgotten = std::binary_search(gone.begin(), gone.end(), k);
    auto a = late.get(k);
    auto b = fresh.get(k);
    ASSERT_TRUE(a.isOk() && b.isOk()) << k.toString();
    EXPECT_TRUE(late.isBuilt(k)) << k.toString();
    if (forgotten) continue;
    ++kept;
    // A tile released before its measure keeps its mesh until measured,
    // then lets it go; compare the mesh it was measured from.
    if (i % 2 == 0) {
      EXPECT_TRUE((*a)->meshReleased) << k.toString() << ": released before measuring, kept after";
      auto mesh = late.mesh(k);
      ASSERT_TRUE(mesh.isOk());
      Tile rebuilt{**mesh, (*a)->bounds, (*a)->triangles};
      testing::expectSameTile(rebuilt, **b, k.toString());
    } else {
      EXPECT_FALSE((*a)->meshReleased) << k.toString();
      testing::expectSameTile(**a, **b, k.toString());
    }
  }
  EXPECT_GT(kept, 0);
  // Rebuilt once each, by the comparison above: none by measuring.
  const int64_t released = static_cast<int64_t>((keys.size() + 1) / 2);
  int64_t releasedKept = 0;
  for (size_t i = 0; i < keys.size(); i += 2)
    if (!std::binary_search(gone.begin(), gone.end(), keys[i])) ++releasedKept;
  EXPECT_EQ(late.rebuilt(), releasedKept) << "of " << released << " released meshes";
  std::printf("[ measured ] hand: %zu tiles built for their mesh, an edit forgot %zu, %lld measured later\n",
              keys.size(), gone.size(), static_cast<long long>(kept));
}

}  // namespace
}  // namespace tessera
