// The error of a tile (core/view/tile_error.h) against exact limits three
// levels finer: at every point of the level-(L+3) lattice inside every face a
// tile shows, the distance from the exact limit to the flat triangle at the
// same parameters stays within the tile's error. The largest ratio to the
// midpoint departure (the bound's 4/3) is printed.
#include <gtest/gtest.h>

#include <random>
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
  int withDeepOffsets = 0, withDeepTags = 0;  // tiles edits more than a level below reach
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
      out.withDeepOffsets += b->deepOffsets > 0 ? 1 : 0;
      ++out.tiles;
      if (b->deepTags) {
        // No bound is claimed: a view refines such a tile while it shows.
        ++out.withDeepTags;
        continue;
      }
      EXPECT_LE(worst, b->error * (1 + 1e-9) + 1e-12) << name << " " << t.toString() << ": midpoints "
                                                      << b->midpoints << ", deep offsets " << b->deepOffsets;
      if (worst > b->error * (1 + 1e-9) + 1e-12) out.withinBound = false;
      if (b->midpoints > 0 && b->deepOffsets == 0)
        out.worstRatioToMidpoints = std::max(out.worstRatioToMidpoints, worst / b->midpoints);
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

// Where edits, tags and interpolating vertices reach the next level, a
// tile reads it from the hierarchy (grown there) instead of from its own
// level's stencils: the bound must hold there too, against the dense
// evaluation of the same edits.
TEST(TileError, TheBoundHoldsWhereEditsTagsAndInterpolatingVerticesReachTheNextLevel) {
  Measured m;
  const testing::TestMesh mesh =
      testing::withRandomTags(testing::withJitter(testing::torus(8, 6), 0.05, 7), 0.15, 0.05, 8);
  auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = 5});
  ASSERT_TRUE(doc.isOk());
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(-1, 1);
  int edits = 0;
  for (int i = 0; i < 32; ++i) {
    const int level = 1 + i % 4;
    const VertexId v(level, rng() % doc->counts().vertices(level));
    const VertexId ids[] = {v};
    if (i % 6 == 5) {
      edits += doc->setEdgeSharpness(EdgeId(level, rng() % doc->counts().edges(level)), 1.5f).isOk();
    } else if (i % 6 == 4) {
      edits +=
          doc->setInterpolation(VertexId(level - 1, rng() % doc->counts().vertices(level - 1)), true).isOk();
    } else {
      edits += doc->moveBy(ids, Vec3(unit(rng), unit(rng), unit(rng)) * 0.05).isOk();
    }
  }
  EXPECT_GE(edits, 24);
  measure(*doc, "edited tagged torus", 3, m);
  // The hierarchy's next level was read at edits, not only at semi-sharp edges.
  int notPredicted = 0;
  for (int l = 0; l + 1 < doc->hierarchy().numLevels(); ++l) {
    const Level& level = doc->hierarchy().level(l).mesh;
    for (Index e = 0; e < level.numEdges(); ++e) {
      const auto& ends = level.edgeVertices[e];
      if (!doc->hierarchy().level(l).isComplete(ends[0]) || !doc->hierarchy().level(l).isComplete(ends[1]))
        continue;
      notPredicted += doc->hierarchy().edgeChildIsPredicted(l, e) ? 0 : 1;
    }
  }
  EXPECT_GT(notPredicted, 0);
  std::printf(
      "[ measured ] %d tiles near %d edits (%d edges read from the next level; %d tiles with moves and %d "
      "with tags "
      "more than a level below)\n",
      m.tiles, edits, notPredicted, m.withDeepOffsets, m.withDeepTags);
  EXPECT_TRUE(m.withinBound);
  EXPECT_GT(m.withDeepOffsets, 0);
  EXPECT_LT(m.withDeepTags, m.tiles);
}

}  // namespace
}  // namespace tessera
