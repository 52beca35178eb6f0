// The error of a tile (core/view/tile_error.h) against exact limits three
// levels finer: at every point of the level-(L+3) lattice inside every face a
// tile shows, the distance from the exact limit to the flat triangle at the
// same parameters stays within the tile's error. The largest ratio to the
// midpoint departure (the bound's 4/3) is printed.
#include <gtest/gtest.h>

#include <unordered_map>

#include "core/document/document_evaluator.h"
#include "core/io/mesh_import.h"
#include "core/loop/limit.h"
#include "core/tessellation/region_lattice.h"
#include "core/view/tile_builder.h"
#include "core/view/tile_error.h"
#include "support/procedural_meshes.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

constexpr int kDepth = 3;

struct Measured {
  double worstRatioToMidpoints = 0;  // true error / midpoint departure
  int tiles = 0;
  bool withinBound = true;
};

void measure(Document& doc, const std::string& name, int maxTileLevel, Measured& out) {
  const TileTree tree = TileTree::build(doc.baseTopology(), doc.counts(), doc.counts().maxLevel());
  std::vector<TileKey> level = tree.roots();
  for (int l = 0; l <= maxTileLevel; ++l) {
    auto dense =
        evaluateDocument(doc.baseTopology(), doc.basePoints(), doc.options().loop, doc.edits(), l + kDepth);
    ASSERT_TRUE(dense.isOk()) << dense.status().message();
    const Level& fine = dense->levels[l + kDepth];
    for (const TileKey& t : level) {
      auto mesh = buildTile(doc, tree, t);
      ASSERT_TRUE(mesh.isOk()) << mesh.status().message();
      auto b = tileBounds(doc, tree, t, *mesh);
      ASSERT_TRUE(b.isOk()) << t.toString() << ": " << b.status().message();
      std::unordered_map<uint64_t, Vec3> shown;
      for (size_t v = 0; v < mesh->positions.size(); ++v) shown[mesh->vertexIds[v]] = mesh->positions[v];
      double worst = 0, outside = -1;
      for (const FaceId& f : tree.facesShown(t)) {
        auto frame = regionFrame(doc.hierarchy(), doc.counts(), f);
        ASSERT_TRUE(frame.isOk()) << frame.status().message();
        auto lattice = RegionLattice::build(*frame, kDepth);
        ASSERT_TRUE(lattice.isOk());
        const int n = lattice->side();
        const Vec3 p0 = shown.at(lattice->idAt(0, 0)->packed()), p1 = shown.at(lattice->idAt(n, 0)->packed()),
                   p2 = shown.at(lattice->idAt(0, n)->packed());
        for (int u = 0; u <= n; ++u) {
          for (int v = 0; u + v <= n; ++v) {
            const VertexId id = *lattice->idAt(u, v);
            const Vec3 exact = limitFrame(fine, static_cast<Index>(id.index()), dense->points[l + kDepth],
                                          doc.options().loop.creaseMethod)
                                   .position;
            const double s = static_cast<double>(u) / n, w = static_cast<double>(v) / n;
            worst = std::max(worst, (exact - ((1 - s - w) * p0 + s * p1 + w * p2)).norm());
            outside = std::max(outside, (exact - b->sphere.centre).norm() - b->sphere.radius);
          }
        }
      }
      EXPECT_LE(worst, b->error * (1 + 1e-9) + 1e-12)
          << name << " " << t.toString() << ": midpoints " << b->midpoints;
      if (worst > b->error * (1 + 1e-9) + 1e-12) out.withinBound = false;
      if (b->midpoints > 0)
        out.worstRatioToMidpoints = std::max(out.worstRatioToMidpoints, worst / b->midpoints);
      ++out.tiles;
      EXPECT_LE(outside, 1e-12) << name << " " << t.toString() << ": the sphere holds every exact point";
    }
    std::vector<TileKey> next;
    for (const TileKey& t : level)
      for (const TileKey& c : tree.children(t)) next.push_back(c);
    level = std::move(next);
  }
}

TEST(TileError, TheErrorBoundsTheExactLimitThreeLevelsFiner) {
  Measured m;
  auto cube = testing::creasedCube();
  ASSERT_TRUE(cube.isOk());
  auto cubeDoc = Document::create(*cube, {.maxLevel = 6});
  ASSERT_TRUE(cubeDoc.isOk());
  measure(*cubeDoc, "creased cube", 2, m);
  for (const testing::TestMesh& mesh :
       {testing::withJitter(testing::torus(8, 6), 0.05, 1),
        testing::withJitter(testing::doubleTorus(), 0.03, 2), testing::openGrid(5, 4)}) {
    auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = 5});
    ASSERT_TRUE(doc.isOk());
    measure(*doc, mesh.name, 3, m);
  }
  // A real scanned mesh: CGAL's hand, 2,390 faces.
  auto hand = importMesh(testing::cgalMeshPath("hand.off"));
  ASSERT_TRUE(hand.isOk());
  auto handDoc = Document::create(*hand, {.maxLevel = 5});
  ASSERT_TRUE(handDoc.isOk());
  measure(*handDoc, "hand", 1, m);
  std::printf("[ measured ] %d tiles: exact error at most %.3f times the midpoint departure (bound 4/3)\n",
              m.tiles, m.worstRatioToMidpoints);
  EXPECT_TRUE(m.withinBound);
  EXPECT_GT(m.tiles, 60);
}

}  // namespace
}  // namespace tessera
