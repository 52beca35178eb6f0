// A view's tiles as the client library assembles them (client/lib/
// document_view.h closedTilePositions, core/view/tile_assembly.h): each
// tile's boundary is summarised once and kept while the tile is held, so
// the summary must go when a delta changes the tile. Here an edit moves
// tiles that meet coarser neighbours, and the assembly after the delta must
// be the one made from scratch, watertight. No server: tiles are selected,
// built and encoded as a server does (core/view), and the messages are
// applied to the client's DocumentView.
#include <gtest/gtest.h>

#include <set>

#include "client/lib/document_view.h"
#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/tessellation/document_grid.h"
#include "core/view/tile_assembly.h"
#include "core/view/tile_catalogue.h"
#include "core/view/tile_encoding.h"
#include "core/view/tile_selection.h"
#include "support/cameras.h"
#include "support/test_meshes.h"
#include "support/tile_gaps.h"

namespace tessera {
namespace {

constexpr uint64_t kDoc = 1;

// The tiles `keys` of `doc` as it is now, encoded as a server encodes them.
std::vector<wire::Region> encodeTiles(Document& doc, const std::vector<TileKey>& keys,
                                      const QuantizationGrid& grid, uint64_t version) {
  TileCatalogue catalogue(doc);
  std::vector<wire::Region> out;
  for (const TileKey& key : keys) {
    auto tile = catalogue.get(key);
    EXPECT_TRUE(tile.isOk()) << tile.status().message();
    if (!tile.isOk()) return {};
    auto encoded = encodeTile(doc, key, (*tile)->mesh, grid, version);
    EXPECT_TRUE(encoded.isOk()) << encoded.status().message();
    if (!encoded.isOk()) return {};
    wire::Region r;
    r.set_region_id(key.regionId());
    r.set_draco(*encoded->bytes);
    out.push_back(std::move(r));
  }
  return out;
}

// The view's assembly, and the one closeCracks makes from its tiles with
// every boundary summarised afresh.
struct Assembly {
  std::vector<uint64_t> ids;
  std::vector<const RegionMesh*> meshes;
  std::vector<std::vector<Vec3>> held, fresh;
  int64_t moved = 0;
};
Assembly assemble(const client::DocumentView& view) {
  Assembly a;
  for (auto& [id, positions] : view.closedTilePositions(&a.moved)) {
    a.ids.push_back(id);
    a.meshes.push_back(&view.regions().at(id));
    a.held.push_back(std::move(positions));
  }
  a.fresh = closeCracks(a.meshes);
  return a;
}

TEST(DocumentViewAssembly, ATileAnEditMovesClosesItsNeighboursCracksWhereItIsNow) {
  auto mesh = importMesh(testing::cgalMeshPath("hand.off"));
  ASSERT_TRUE(mesh.isOk()) << mesh.status().message();
  auto created = Document::create(*mesh, {.maxLevel = 4});
  ASSERT_TRUE(created.isOk()) << created.status().message();
  Document doc = std::move(*created);
  auto grid = documentGrid(doc);
  ASSERT_TRUE(grid.isOk()) << grid.status().message();
  Vec3 lo = doc.basePoints()[0], hi = lo;
  for (const Vec3& p : doc.basePoints()) lo = testing::min(lo, p), hi = testing::max(hi, p);
  const Vec3 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * (hi - lo).norm();
  // Close on base vertex 0: fine tiles there, coarser ones around.
  const Vec3 near = doc.basePoints()[0];
  const Vec3 out = (near - centre).normalized();
  std::vector<TileKey> keys;
  {
    TileCatalogue catalogue(doc);
    auto selection = selectTiles(testing::lookAt(near + 0.3 * radius * out, near, 1920, 1080), catalogue);
    ASSERT_TRUE(selection.isOk()) << selection.status().message();
    for (const SelectedTile& t : selection->tiles) keys.push_back(t.key);
  }
  client::DocumentView view(kDoc);
  wire::ServerMessage snapshot;
  snapshot.mutable_snapshot()->set_document_id(kDoc);
  snapshot.mutable_snapshot()->set_version(1);
  for (wire::Region& r : encodeTiles(doc, keys, *grid, 1)) *snapshot.mutable_snapshot()->add_regions() = r;
  ASSERT_TRUE(view.apply(snapshot).isOk());
  const Assembly before = assemble(view);
  ASSERT_GT(before.moved, 0) << "the view must show tiles of several levels side by side";
  EXPECT_TRUE(before.held == before.fresh);

  // The edit: a corner of the base face under a tile whose cracks were
  // closed moves out. The delta carries the tiles whose payload changed, as
  // a server's does.
  int corner = -1;
  {
    TileCatalogue catalogue(doc);
    for (size_t i = 0; i < before.ids.size() && corner < 0; ++i) {
      if (before.held[i] == before.meshes[i]->positions) continue;
      const FaceId face = catalogue.tree().facesShown(TileKey::fromRegionId(before.ids[i])).front();
      corner = doc.baseTopology().triangles[face.index() >> (2 * face.level())][0];
    }
  }
  ASSERT_GE(corner, 0);
  const VertexId moved[] = {VertexId(0, static_cast<uint64_t>(corner))};
  ASSERT_TRUE(doc.moveBy(moved, 0.05 * radius * (doc.basePoints()[corner] - centre).normalized()).isOk());
  wire::ServerMessage delta;
  delta.mutable_delta()->set_document_id(kDoc);
  delta.mutable_delta()->set_from_version(1);
  delta.mutable_delta()->set_to_version(2);
  std::set<uint64_t> changed;
  const auto again = encodeTiles(doc, keys, *grid, 2);
  ASSERT_EQ(again.size(), keys.size());
  for (size_t i = 0; i < keys.size(); ++i) {
    const RegionMesh& held = view.regions().at(keys[i].regionId());
    auto decoded = decodeRegion(again[i].draco());
    ASSERT_TRUE(decoded.isOk()) << decoded.status().message();
    if (decoded->second.positions == held.positions) continue;
    changed.insert(keys[i].regionId());
    *delta.mutable_delta()->add_regions() = again[i];
  }
  ASSERT_FALSE(changed.empty());
  ASSERT_TRUE(view.apply(delta).isOk());

  const Assembly after = assemble(view);
  size_t differ = 0;
  for (size_t i = 0; i < after.held.size(); ++i) differ += after.held[i] != after.fresh[i];
  EXPECT_EQ(differ, 0u) << "tiles whose assembly after the delta is not the one made from scratch";
  EXPECT_EQ(testing::unmatchedEdges(after.meshes, after.held, radius), 0);
  // The edit reached tiles whose cracks were closed: otherwise the held
  // summaries would not have been put to the test.
  int changedAndClosed = 0;
  const auto closed = view.closedTilePositions();
  for (const auto& [id, mesh] : view.regions()) {
    if (changed.count(id) && closed.at(id) != mesh.positions) ++changedAndClosed;
  }
  EXPECT_GT(changedAndClosed, 0) << changed.size() << " tiles changed, none with a crack closed";
}

}  // namespace
}  // namespace tessera
