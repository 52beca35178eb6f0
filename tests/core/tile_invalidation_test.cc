// Which tiles an edit reached (core/view/tile_invalidation.h): after random
// moves and crease edits at random levels, every tile the catalogue kept
// equals, bit for bit in its mesh and bounds, the tile built afresh from
// the edited document; and on a model of many base faces an edit forgets
// only the tiles around it. The same on Catmull-Clark documents.
#include <gtest/gtest.h>

#include <random>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/schemes/polygon_reader.h"
#include "core/view/tile_catalogue.h"
#include "support/polygon_meshes.h"
#include "support/same_tile.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

std::vector<TileKey> everyTile(const TileTree& tree) {
  std::vector<TileKey> all, frontier = tree.roots();
  while (!frontier.empty()) {
    std::vector<TileKey> next;
    for (const TileKey& k : frontier) {
      all.push_back(k);
      for (const TileKey& c : tree.children(k)) next.push_back(c);
    }
    frontier = std::move(next);
  }
  return all;
}

// `local`: a model of many base faces, where an edit reaches few of them.
void checkEdits(Document& doc, const std::string& name, uint32_t seed, bool local) {
  TileCatalogue held(doc);
  const std::vector<TileKey> all = everyTile(held.tree());
  held.prepare(all);
  for (const TileKey& k : all) ASSERT_TRUE(held.get(k).isOk()) << name << " " << k.toString();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1, 1);
  int64_t forgotten = 0, kept = 0;
  for (int edit = 0; edit < 8; ++edit) {
    const int level = static_cast<int>(rng() % (doc.counts().maxLevel() + 1));
    const VertexId v(level, rng() % doc.counts().vertices(level));
    const std::string where = name + " edit " + std::to_string(edit) + " at " + v.toString();
    if (edit % 3 == 2 && level < doc.counts().maxLevel()) {
      // A crease: the edges of this level from its first vertex's ring.
      const EdgeId e(level, rng() % doc.counts().edges(level));
      ASSERT_TRUE(doc.setEdgeSharpness(e, 2.5f).isOk()) << where;
    } else {
      const VertexId ids[] = {v};
      ASSERT_TRUE(doc.moveBy(ids, Vec3(unit(rng), unit(rng), unit(rng)) * 0.05).isOk()) << where;
    }
    const std::vector<TileKey> gone =
        held.forget(TouchedTiles(doc.hierarchy(), held.tree(), doc.lastUpdate().limits));
    forgotten += static_cast<int64_t>(gone.size());
    TileCatalogue fresh(doc);
    fresh.prepare(all);
    for (const TileKey& k : all) {
      if (std::binary_search(gone.begin(), gone.end(), k)) continue;
      ++kept;
      auto a = held.get(k);
      auto b = fresh.get(k);
      ASSERT_TRUE(a.isOk() && b.isOk()) << where;
      testing::expectSameTile(**a, **b, where + " " + k.toString());
    }
    held.prepare(all);
    for (const TileKey& k : all) ASSERT_TRUE(held.get(k).isOk());
  }
  std::printf("[ measured ] %s: %zu tiles, 8 edits forgot %lld and kept %lld\n", name.c_str(), all.size(),
              static_cast<long long>(forgotten), static_cast<long long>(kept));
  EXPECT_GT(forgotten, 0) << name;
  EXPECT_GT(kept, 0) << name;
  if (local) {
    EXPECT_GT(kept, 10 * forgotten) << name << ": an edit forgets only the tiles around it";
  }
}

TEST(TileInvalidation, TilesAnEditDidNotReachEqualTilesBuiltAfresh) {
  auto cube = testing::creasedCube();
  ASSERT_TRUE(cube.isOk());
  auto cubeDoc = Document::create(*cube, {.maxLevel = 7});
  ASSERT_TRUE(cubeDoc.isOk());
  checkEdits(*cubeDoc, "creased cube", 3, false);
  auto hand = importMesh(testing::cgalMeshPath("hand.off"));
  ASSERT_TRUE(hand.isOk());
  auto handDoc = Document::create(*hand, {.maxLevel = 3});
  ASSERT_TRUE(handDoc.isOk());
  checkEdits(*handDoc, "hand", 7, true);
}

// The same on the quad split: a face's ancestors and base face follow the
// split's counts (n children under a base n-gon), not Loop's 4^k.
TEST(TileInvalidation, OnTheQuadSplitTilesAnEditDidNotReachEqualTilesBuiltAfresh) {
  const testing::PolyTestMesh prism = testing::mixedPrism(6, false);
  auto prismDoc = Document::create(prism.topology, prism.points,
                                   {.maxLevel = 6, .scheme = DocumentScheme::kCatmullClark});
  ASSERT_TRUE(prismDoc.isOk()) << prismDoc.status().message();
  checkEdits(*prismDoc, "mixed prism", 4, false);
  auto torus = schemes::importPolygonMesh(testing::cgalMeshPath("double-torus-example.off"), "");
  ASSERT_TRUE(torus.isOk()) << torus.status().message();
  auto torusDoc = Document::create(torus->topology, torus->points,
                                   {.maxLevel = 3, .scheme = DocumentScheme::kCatmullClark});
  ASSERT_TRUE(torusDoc.isOk()) << torusDoc.status().message();
  checkEdits(*torusDoc, "double torus", 8, false);
}

TEST(TileInvalidation, RegionIdsNameTilesBothWays) {
  for (const TileKey& k : {TileKey{0, FaceId(0, 17).packed()}, TileKey{4, FaceId(0, 3).packed()},
                           TileKey{5, FaceId(0, 12).packed()}, TileKey{9, FaceId(4, 1234567).packed()}}) {
    EXPECT_EQ(TileKey::fromRegionId(k.regionId()), k) << k.toString();
  }
  EXPECT_NE(TileKey({5, FaceId(0, 12).packed()}).regionId(), TileKey({4, FaceId(0, 12).packed()}).regionId());
}

}  // namespace
}  // namespace tessera
