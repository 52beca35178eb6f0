// The error of a Catmull-Clark document's tiles (core/view/tile_error.h, the
// quad split) against exact limits three levels finer: at every point of
// the level-(L+3) lattice inside every quad a tile shows, the distance from
// the exact limit to the flat quad at the same parameters (its two
// triangles on the first diagonal) stays within the tile's error. A base
// n-gon of other than four corners is shown as a fan, which has no such
// parameters: there the distance to the fan's nearest point is measured,
// and said to be that. The exact limit is Catmull-Clark's limit mask at
// the finer level of the from-scratch evaluation (core/catmark/limit.h),
// which is exact away from semi-sharp features that have not decayed: the
// documents carry infinitely sharp creases and corners (sharpness 10,
// Sdc's infinite) and moves at every level, no semi-sharp tag.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <unordered_map>

#include "core/catmark/limit.h"
#include "core/render/surface_distance.h"
#include "core/schemes/polygon_reader.h"
#include "core/tessellation/region_lattice.h"
#include "core/view/tile_builder.h"
#include "core/view/tile_error.h"
#include "support/polygon_meshes.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

constexpr int kDepth = 3;

struct Measured {
  double worstRatioToMidpoints = 0;  // true error / midpoint departure, quads without deep moves
  double worstFanRatio = 0;          // the same for tiles with base n-gons
  int tiles = 0, faces = 0, withDeepOffsets = 0, withNgons = 0;
  bool withinBound = true;
};

// The flat quad at (s, w) in [0, 1]^2: corners 0..3 at (0,0), (1,0), (1,1),
// (0,1), triangles 0 1 2 and 0 2 3.
Vec3 flatQuad(const std::array<Vec3, 4>& c, double s, double w) {
  if (w <= s) return (1 - s) * c[0] + (s - w) * c[1] + w * c[2];
  return (1 - w) * c[0] + s * c[2] + (w - s) * c[3];
}

void measure(Document& doc, const PolyTopology& base, const std::string& name, int maxTileLevel,
             Measured& out) {
  const TileTree tree = TileTree::build(base, doc.counts(), doc.counts().maxLevel());
  std::vector<TileKey> level = tree.roots();
  for (int l = 0; l <= maxTileLevel; ++l) {
    auto dense = doc.evaluate(l + kDepth);
    ASSERT_TRUE(dense.isOk()) << dense.status().message();
    const Level& fine = (*dense)->levels[l + kDepth];
    const auto finePoints = (*dense)->points[l + kDepth];
    auto exactAt = [&](VertexId id) {
      return catmarkLimitFrame(fine, static_cast<Index>(id.index()), finePoints, doc.options().loop).position;
    };
    for (const TileKey& t : level) {
      auto mesh = buildTile(doc, tree, t);
      ASSERT_TRUE(mesh.isOk()) << mesh.status().message();
      auto b = tileBounds(doc, tree, t, *mesh);
      ASSERT_TRUE(b.isOk()) << t.toString() << ": " << b.status().message();
      ASSERT_FALSE(b->deepTags) << "only moves lie deep in these documents";
      std::unordered_map<uint64_t, Vec3> shown;
      for (size_t v = 0; v < mesh->positions.size(); ++v) shown[mesh->vertexIds[v]] = mesh->positions[v];
      double worst = 0, outside = -1;
      bool ngon = false;
      for (const FaceId& f : tree.facesShown(t)) {
        ++out.faces;
        if (doc.counts().faceSize(f) == 4) {
          auto frame = regionFrame(doc.hierarchy(), doc.counts(), f);
          ASSERT_TRUE(frame.isOk()) << frame.status().message();
          auto lattice = RegionLattice::build(*frame, kDepth);
          ASSERT_TRUE(lattice.isOk());
          const int n = lattice->side();
          const std::array<Vec3, 4> c{
              shown.at(lattice->idAt(0, 0)->packed()), shown.at(lattice->idAt(n, 0)->packed()),
              shown.at(lattice->idAt(n, n)->packed()), shown.at(lattice->idAt(0, n)->packed())};
          for (int u = 0; u <= n; ++u) {
            for (int v = 0; v <= n; ++v) {
              const Vec3 exact = exactAt(*lattice->idAt(u, v));
              worst = std::max(worst, (exact - flatQuad(c, double(u) / n, double(v) / n)).norm());
              outside = std::max(outside, (exact - b->sphere.centre).norm() - b->sphere.radius);
            }
          }
          continue;
        }
        // A base n-gon: its fan from the corners' shown limits, against the
        // exact points of its quads' lattices one level down.
        ngon = true;
        std::vector<Vec3> fan;
        const Index local = doc.hierarchy().level(0).findFace(f.index());
        for (Index v : doc.hierarchy().level(0).mesh.faceVerticesOf(local))
          fan.push_back(shown.at(VertexId(0, doc.hierarchy().level(0).vertexIds[v]).packed()));
        for (int k = 0; k < doc.counts().faceSize(f); ++k) {
          auto frame = regionFrame(doc.hierarchy(), doc.counts(), doc.counts().childFace(f, k));
          ASSERT_TRUE(frame.isOk()) << frame.status().message();
          auto lattice = RegionLattice::build(*frame, kDepth - 1);
          ASSERT_TRUE(lattice.isOk());
          const int n = lattice->side();
          for (int u = 0; u <= n; ++u) {
            for (int v = 0; v <= n; ++v) {
              const Vec3 exact = exactAt(*lattice->idAt(u, v));
              double nearest = 1e300;
              for (size_t j = 1; j + 1 < fan.size(); ++j)
                nearest =
                    std::min(nearest, (exact - closestOnTriangle(exact, fan[0], fan[j], fan[j + 1])).norm());
              worst = std::max(worst, nearest);
              outside = std::max(outside, (exact - b->sphere.centre).norm() - b->sphere.radius);
            }
          }
        }
      }
      ++out.tiles;
      out.withDeepOffsets += b->deepOffsets > 0 ? 1 : 0;
      out.withNgons += ngon ? 1 : 0;
      EXPECT_LE(worst, b->error * (1 + 1e-9) + 1e-12) << name << " " << t.toString() << ": midpoints "
                                                      << b->midpoints << ", deep offsets " << b->deepOffsets;
      if (worst > b->error * (1 + 1e-9) + 1e-12) out.withinBound = false;
      if (b->midpoints > 0 && b->deepOffsets == 0) {
        double& ratio = ngon ? out.worstFanRatio : out.worstRatioToMidpoints;
        ratio = std::max(ratio, worst / b->midpoints);
      }
      EXPECT_LE(outside, 1e-12) << name << " " << t.toString() << ": the sphere holds every exact point";
    }
    std::vector<TileKey> next;
    for (const TileKey& t : level)
      for (const TileKey& c : tree.children(t)) next.push_back(c);
    level = std::move(next);
  }
}

// Infinitely sharp creases on random interior base edges and a corner,
// and moves at levels 0 to `deepest`, from a fixed seed.
void tagAndMove(Document& doc, uint32_t seed, int moves, int deepest) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1, 1);
  const LevelCounts& counts = doc.counts();
  int creases = 0;
  for (int i = 0; i < 40 && creases < 4; ++i) {
    // Boundary edges are refused (they are sharp already).
    creases += doc.setEdgeSharpness(EdgeId(0, rng() % counts.edges(0)), 10.0f).isOk() ? 1 : 0;
  }
  EXPECT_EQ(creases, 4);
  EXPECT_TRUE(doc.setVertexSharpness(VertexId(0, rng() % counts.vertices(0)), 10.0f).isOk());
  for (int i = 0; i < moves; ++i) {
    const VertexId v(i % (deepest + 1), rng() % counts.vertices(i % (deepest + 1)));
    EXPECT_TRUE(doc.moveBy(std::span(&v, 1), Vec3(unit(rng), unit(rng), unit(rng)) * 0.04).isOk());
  }
}

TEST(QuadTileError, TheErrorBoundsTheExactLimitThreeLevelsFiner) {
  Measured m;
  int seed = 1;
  // Moves down to level 1 only (every tile's bound is its midpoints'), or
  // to level 3 (deep offsets in the bound).
  for (const auto& [mesh, deepest] : std::vector<std::pair<testing::PolyTestMesh, int>>{
           {testing::withPolyJitter(testing::quadTorus(8, 6), 0.05, 1), 3},
           {testing::withPolyJitter(testing::quadTorus(8, 6), 0.05, 2), 1},
           {testing::mixedPrism(6, false), 1},
           {testing::mixedPrism(5, true), 3},
           {testing::quadGrid(5, 4), 1}}) {
    auto doc = Document::create(mesh.topology, mesh.points,
                                {.maxLevel = 3 + kDepth, .scheme = DocumentScheme::kCatmullClark});
    ASSERT_TRUE(doc.isOk()) << doc.status().message();
    tagAndMove(*doc, ++seed, 12, deepest);
    measure(*doc, mesh.topology, mesh.name, 3, m);
  }
  // A real quad mesh: CGAL's double torus, 1,536 quads.
  auto real = schemes::importPolygonMesh(testing::cgalMeshPath("double-torus-example.off"), "");
  ASSERT_TRUE(real.isOk()) << real.status().message();
  auto doc = Document::create(real->topology, real->points,
                              {.maxLevel = 4, .scheme = DocumentScheme::kCatmullClark});
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  tagAndMove(*doc, 9, 8, 3);
  measure(*doc, real->topology, "double torus", 1, m);
  std::printf(
      "[ measured ] %d tiles, %d faces (%d tiles with base n-gons, %d with moves two levels below): exact "
      "error at most %.3f times the midpoint departure on quads (bound 4/3), %.3f on fans (nearest points)\n",
      m.tiles, m.faces, m.withNgons, m.withDeepOffsets, m.worstRatioToMidpoints, m.worstFanRatio);
  EXPECT_TRUE(m.withinBound);
  EXPECT_GT(m.faces, 10000);
  EXPECT_GT(m.withNgons, 0);
  EXPECT_GT(m.withDeepOffsets, 0);
}

}  // namespace
}  // namespace tessera
