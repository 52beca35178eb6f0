// A view's tiles (core/view/tile_selection.h, tile_assembly.h) at random
// cameras around real meshes: the selection covers the surface once; every
// visible tile's error projects within the tolerance (or the tile is the
// deepest there is); tiles wholly outside the frustum are not refined; each
// tile is built once however many views ask; the budget raises the
// tolerance instead of dropping tiles; a walk with an allowance of new
// tiles shows coarser whole cuts and then the same tiles; and the assembled surface, cracks
// closed, has no gaps: every boundary edge of every tile lies on a boundary
// edge of another. Without closing the cracks the same check fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <unordered_map>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/view/tile_assembly.h"
#include "core/view/tile_selection.h"
#include "support/procedural_meshes.h"
#include "support/test_meshes.h"
#include "support/tile_gaps.h"

namespace tessera {
namespace {

struct Model {
  std::string name;
  Document doc;
  Vec3 centre;
  double radius;
};

Model model(const std::string& name, Document doc) {
  Vec3 lo = doc.basePoints()[0], hi = lo;
  for (const Vec3& p : doc.basePoints()) lo = testing::min(lo, p), hi = testing::max(hi, p);
  return {name, std::move(doc), 0.5 * (lo + hi), 0.5 * (hi - lo).norm()};
}

View randomView(const Model& m, std::mt19937& rng, int width, int height) {
  std::uniform_real_distribution<double> unit(-1, 1);
  Vec3 dir(unit(rng), unit(rng), unit(rng));
  while (dir.norm() < 0.1) dir = Vec3(unit(rng), unit(rng), unit(rng));
  View v;
  const double distance = m.radius * (0.6 + 3 * std::abs(unit(rng)));
  v.eye = m.centre + distance * dir.normalized();
  const Vec3 look = m.centre + 0.4 * m.radius * Vec3(unit(rng), unit(rng), unit(rng));
  v.forward = look - v.eye;
  v.up = std::abs(v.forward.normalized()[1]) > 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  v.fovYRadians = 50 * std::numbers::pi / 180;
  v.nearDistance = m.radius * 1e-3;
  v.width = width;
  v.height = height;
  v.tolerancePixels = 1;
  return v;
}

TEST(TileSelection, RandomCamerasGetAWatertightSurfaceWithinTheirTolerance) {
  std::vector<Model> models;
  auto cube = testing::creasedCube();
  ASSERT_TRUE(cube.isOk());
  auto cubeDoc = Document::create(*cube, {.maxLevel = 6});
  ASSERT_TRUE(cubeDoc.isOk());
  models.push_back(model("creased cube", std::move(*cubeDoc)));
  auto hand = importMesh(testing::cgalMeshPath("hand.off"));
  ASSERT_TRUE(hand.isOk());
  auto handDoc = Document::create(*hand, {.maxLevel = 4});
  ASSERT_TRUE(handDoc.isOk());
  models.push_back(model("hand", std::move(*handDoc)));
  std::mt19937 rng(21);
  int64_t crackedWithoutClosing = 0, mixedLevels = 0, hidden = 0;
  for (Model& m : models) {
    TileCatalogue catalogue(m.doc);
    for (int camera = 0; camera < 12; ++camera) {
      const View view = camera % 2 ? randomView(m, rng, 390, 844) : randomView(m, rng, 1920, 1080);
      const std::string where = m.name + " camera " + std::to_string(camera);
      auto s = selectTiles(view, catalogue);
      ASSERT_TRUE(s.isOk()) << where << ": " << s.status().message();
      // Covers every base face once: the parametric areas add up to 1.
      std::map<uint64_t, double> area;
      std::vector<const RegionMesh*> meshes;
      std::map<int, int> levels;
      for (const SelectedTile& t : s->tiles) {
        auto tile = catalogue.get(t.key);
        ASSERT_TRUE(tile.isOk());
        meshes.push_back(&(*tile)->mesh);
        ++levels[t.key.level];
        for (const FaceId& f : catalogue.tree().facesShown(t.key))
          area[f.index() >> (2 * f.level())] += std::ldexp(1.0, -2 * f.level());
        if (t.visible && t.key.level < m.doc.counts().maxLevel()) {
          EXPECT_LE(t.projectedError, view.tolerancePixels) << where << " " << t.key.toString();
        }
        if (!t.visible && t.key.level > 0) {
          // Nothing is refined out of view: a hidden tile is a root, or the
          // sibling of a visible one its parent was refined for.
          auto parent = catalogue.get(catalogue.tree().parent(t.key));
          ASSERT_TRUE(parent.isOk());
          EXPECT_FALSE(view.outside((*parent)->bounds.sphere)) << where << " " << t.key.toString();
          ++hidden;
        }
      }
      ASSERT_EQ(area.size(), m.doc.counts().faces(0)) << where;
      for (const auto& [face, a] : area) ASSERT_NEAR(a, 1.0, 1e-12) << where << " base face " << face;
      if (levels.size() > 1) ++mixedLevels;
      // Watertight once the cracks are closed; not before, where levels meet.
      int64_t moved = 0;
      const auto closed = closeCracks(meshes, &moved);
      EXPECT_EQ(testing::unmatchedEdges(meshes, closed, m.radius), 0)
          << where << ", " << s->tiles.size() << " tiles";
      std::vector<std::vector<Vec3>> raw;
      for (const RegionMesh* mesh : meshes) raw.push_back(mesh->positions);
      const int64_t open = testing::unmatchedEdges(meshes, raw, m.radius);
      if (moved > 0) {
        EXPECT_GT(open, 0) << where << ": moved vertices closed real cracks";
      }
      crackedWithoutClosing += open;
    }
    // Every tile built once, however many cameras wanted it.
    std::printf("[ measured ] %s: %lld tiles built for 12 cameras\n", m.name.c_str(),
                static_cast<long long>(catalogue.built()));
  }
  EXPECT_GT(mixedLevels, 6) << "most cameras see several levels at once";
  EXPECT_GT(crackedWithoutClosing, 0);
  EXPECT_GT(hidden, 0) << "some cameras see part of the surface only";
}

// Whether the edge between two vertices of level l (packed ids) lies on the
// surface's boundary: it is a half of a half ... of a boundary base edge
// (canonical edge numbering, core/hierarchy/ids.h: a level's first 2 E
// edges are the halves of the parent's E edges).
bool onSurfaceBoundary(const Document& doc, int l, uint64_t a, uint64_t b) {
  auto edge = doc.edgeBetween(VertexId(l, VertexId::fromPacked(a).index()),
                              VertexId(l, VertexId::fromPacked(b).index()));
  if (!edge.isOk()) return false;
  uint64_t e = edge->index();
  for (int k = l; k > 0; --k) {
    if (e >= 2 * doc.counts().edges(k - 1)) return false;  // inside a parent face
    e /= 2;
  }
  return doc.hierarchy().level(0).mesh.edgeFaces[static_cast<Index>(e)][1] == kNoIndex;
}

// On open surfaces the assembled tiles leave no gap but the surface's own
// boundary, and closing the cracks never moves a vertex on that boundary:
// a run of boundary vertices between two a neighbour shares is not a finer
// copy of the neighbour's edge (docs/VIEWS.md "Assembling tiles").
TEST(TileSelection, OpenSurfacesAssembleWithoutGapsAndKeepTheirBoundary) {
  std::vector<Model> models;
  for (const testing::TestMesh& mesh : {testing::withJitter(testing::openGrid(16, 12), 0.05, 3),
                                        testing::withJitter(testing::diskWithPole(9), 0.03, 4)}) {
    auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = 6});
    ASSERT_TRUE(doc.isOk());
    models.push_back(model(mesh.name, std::move(*doc)));
  }
  std::mt19937 rng(23);
  int64_t boundaryEdges = 0, mixedLevels = 0, closedCracks = 0;
  for (Model& m : models) {
    TileCatalogue catalogue(m.doc);
    for (int camera = 0; camera < 16; ++camera) {
      View view = camera % 2 ? randomView(m, rng, 390, 844) : randomView(m, rng, 1920, 1080);
      view.tolerancePixels = camera % 4 < 2 ? 1 : 4;
      const std::string where = m.name + " camera " + std::to_string(camera);
      auto s = selectTiles(view, catalogue);
      ASSERT_TRUE(s.isOk()) << where << ": " << s.status().message();
      std::vector<const RegionMesh*> meshes;
      std::vector<int> levels;
      for (const SelectedTile& t : s->tiles) {
        auto tile = catalogue.get(t.key);
        ASSERT_TRUE(tile.isOk());
        meshes.push_back(&(*tile)->mesh);
        levels.push_back(t.key.level);
      }
      if (std::set<int>(levels.begin(), levels.end()).size() > 1) ++mixedLevels;
      int64_t moved = 0;
      const auto closed = closeCracks(meshes, &moved);
      closedCracks += moved;
      // Per tile, the edges on the surface's boundary, and none of their
      // vertices moved.
      for (size_t i = 0; i < meshes.size(); ++i) {
        const RegionMesh& mesh = *meshes[i];
        for (const auto& t : mesh.triangles) {
          for (int k = 0; k < 3; ++k) {
            const int p = t[k], q = t[(k + 1) % 3];
            if (!onSurfaceBoundary(m.doc, levels[i], mesh.vertexIds[p], mesh.vertexIds[q])) continue;
            ++boundaryEdges;
            EXPECT_EQ(closed[i][p], mesh.positions[p]) << where << ": a boundary vertex moved";
            EXPECT_EQ(closed[i][q], mesh.positions[q]) << where << ": a boundary vertex moved";
          }
        }
      }
      // One boundary test per tile: tile i's edges are of level levels[i].
      std::map<std::pair<uint64_t, uint64_t>, bool> boundary;
      for (size_t i = 0; i < meshes.size(); ++i) {
        for (const auto& t : meshes[i]->triangles) {
          for (int k = 0; k < 3; ++k) {
            uint64_t a = meshes[i]->vertexIds[t[k]], b = meshes[i]->vertexIds[t[(k + 1) % 3]];
            if (a > b) std::swap(a, b);
            boundary.emplace(std::pair(a, b), onSurfaceBoundary(m.doc, levels[i], a, b));
          }
        }
      }
      const auto isBoundary = [&](uint64_t a, uint64_t b) {
        return boundary.at({std::min(a, b), std::max(a, b)});
      };
      EXPECT_EQ(testing::unmatchedEdges(meshes, closed, m.radius, isBoundary), 0)
          << where << ", " << s->tiles.size() << " tiles";
    }
  }
  std::printf(
      "[ measured ] open surfaces: %lld tile edges on the boundary, %lld vertices moved onto coarser edges\n",
      static_cast<long long>(boundaryEdges), static_cast<long long>(closedCracks));
  EXPECT_GT(boundaryEdges, 100);
  EXPECT_GT(mixedLevels, 8) << "most cameras see several levels at once";
  EXPECT_GT(closedCracks, 0);
}

// Many views in one walk (a server choosing for every viewer at once) choose
// what each would alone, budgets included.
TEST(TileSelection, ManyViewsAtOnceChooseWhatEachWouldAlone) {
  auto hand = importMesh(testing::cgalMeshPath("hand.off"));
  ASSERT_TRUE(hand.isOk());
  auto doc = Document::create(*hand, {.maxLevel = 4});
  ASSERT_TRUE(doc.isOk());
  Model m = model("hand", std::move(*doc));
  std::mt19937 rng(17);
  std::vector<View> views;
  std::vector<int64_t> budgets;
  for (int i = 0; i < 10; ++i) {
    views.push_back(randomView(m, rng, i % 2 ? 390 : 1920, i % 2 ? 844 : 1080));
    budgets.push_back(i % 3 == 0 ? 60000 : 0);
  }
  TileCatalogue together(m.doc);
  auto all = selectTilesForEach(views, together, budgets);
  ASSERT_TRUE(all.isOk()) << all.status().message();
  TileCatalogue alone(m.doc);
  for (size_t i = 0; i < views.size(); ++i) {
    auto one = selectTiles(views[i], alone, budgets[i]);
    ASSERT_TRUE(one.isOk());
    ASSERT_EQ((*all)[i].tiles.size(), one->tiles.size()) << "view " << i;
    for (size_t k = 0; k < one->tiles.size(); ++k) EXPECT_EQ((*all)[i].tiles[k].key, one->tiles[k].key) << i;
    EXPECT_EQ((*all)[i].tolerancePixels, one->tolerancePixels) << i;
    if (budgets[i] > 0) {
      EXPECT_LE((*all)[i].triangles, budgets[i]) << i;
    }
  }
}

// Walks of four cameras over the hand, step after step, each with
// `allowance` new tiles and `stopBuilding`: each step builds at most
// `mostNew` (or one tile's children, the progress every walk makes), shows a
// coarser cut of the whole surface meanwhile, and the steps end on what one
// walk without allowance selects. Returns the incomplete steps.
int expectStepsEndOnTheWholeSelection(int64_t allowance, const std::function<bool()>& stopBuilding,
                                      int64_t mostNew) {
  auto hand = importMesh(testing::cgalMeshPath("hand.off"));
  EXPECT_TRUE(hand.isOk());
  if (!hand.isOk()) return 0;
  auto doc = Document::create(*hand, {.maxLevel = 4});
  EXPECT_TRUE(doc.isOk());
  if (!doc.isOk()) return 0;
  Model m = model("hand", std::move(*doc));
  std::mt19937 rng(29);
  std::vector<View> views;
  for (int i = 0; i < 3; ++i) views.push_back(randomView(m, rng, 390, 844));
  views.push_back(randomView(m, rng, 1920, 1080));
  const std::vector<int64_t> budgets(views.size(), 0);
  TileCatalogue whole(m.doc);
  auto expected = selectTilesForEach(views, whole, budgets);
  EXPECT_TRUE(expected.isOk()) << expected.status().message();
  if (!expected.isOk()) return 0;
  for (const TileSelection& s : *expected) EXPECT_TRUE(s.complete);
  size_t mostChildren = 0;
  for (const TileSelection& s : *expected) {
    for (const SelectedTile& t : s.tiles) {
      for (TileKey a = t.key; a.level > 0;) {
        a = whole.tree().parent(a);
        mostChildren = std::max(mostChildren, whole.tree().children(a).size());
      }
    }
  }
  const int64_t mostPerStep = std::max<int64_t>(mostNew, static_cast<int64_t>(mostChildren));
  TileCatalogue stepwise(m.doc);
  // The roots are built by the first walk whatever its allowance.
  (void)selectTilesForEach(views, stepwise, budgets, 0);
  int incompleteSteps = 0;
  for (int steps = 0;; ++steps) {
    EXPECT_LT(steps, 10000) << "the steps never end";
    if (steps >= 10000) return incompleteSteps;
    const int64_t before = stepwise.built();
    auto got = selectTilesForEach(views, stepwise, budgets, allowance, stopBuilding);
    EXPECT_TRUE(got.isOk()) << got.status().message();
    if (!got.isOk()) return incompleteSteps;
    EXPECT_LE(stepwise.built() - before, mostPerStep) << "step " << steps;
    bool complete = true;
    for (const TileSelection& s : *got) {
      complete = complete && s.complete;
      // Every step covers every base face once.
      std::map<uint64_t, double> area;
      for (const SelectedTile& t : s.tiles)
        for (const FaceId& f : stepwise.tree().facesShown(t.key))
          area[f.index() >> (2 * f.level())] += std::ldexp(1.0, -2 * f.level());
      EXPECT_EQ(area.size(), m.doc.counts().faces(0)) << "step " << steps;
      for (const auto& [face, a] : area) EXPECT_NEAR(a, 1.0, 1e-12) << "step " << steps << " face " << face;
    }
    if (complete) {
      for (size_t v = 0; v < views.size(); ++v) {
        EXPECT_EQ((*got)[v].tiles.size(), (*expected)[v].tiles.size()) << "view " << v;
        if ((*got)[v].tiles.size() != (*expected)[v].tiles.size()) continue;
        for (size_t k = 0; k < (*got)[v].tiles.size(); ++k)
          EXPECT_EQ((*got)[v].tiles[k].key, (*expected)[v].tiles[k].key) << "view " << v;
      }
      break;
    }
    ++incompleteSteps;
  }
  EXPECT_EQ(stepwise.built(), whole.built()) << "no tile built twice";
  return incompleteSteps;
}

// A walk with an allowance of new tiles (tile_selection.h).
TEST(TileSelection, AnAllowanceOfNewTilesGivesCoarserCompleteCutsThenTheSameSelection) {
  constexpr int64_t kAllowance = 3;
  const int incompleteSteps = expectStepsEndOnTheWholeSelection(kAllowance, {}, kAllowance);
  std::printf("[ measured ] %d incomplete steps of at most %lld new tiles before the whole selection\n",
              incompleteSteps, static_cast<long long>(kAllowance));
  EXPECT_GT(incompleteSteps, 3) << "the allowance held tiles back";
}

// A walk told to stop building (a server's turn of camera moves once an
// edit waits behind it) makes its first refinement and no other, whatever
// its allowance of tiles; it asks before each refinement that builds.
TEST(TileSelection, AWalkToldToStopBuildingMakesOneRefinementPerStepThenTheSameSelection) {
  int asked = 0;
  const std::function<bool()> editWaits = [&] { return ++asked, true; };
  const int incompleteSteps = expectStepsEndOnTheWholeSelection(1000, editWaits, 0);
  std::printf("[ measured ] %d incomplete steps of one refinement, asked %d times\n", incompleteSteps, asked);
  EXPECT_GT(incompleteSteps, 3) << "the walk stopped building when told";
  EXPECT_GE(asked, incompleteSteps) << "each incomplete step asked";
  int never = 0;
  const std::function<bool()> nothingWaits = [&] { return ++never, false; };
  EXPECT_EQ(expectStepsEndOnTheWholeSelection(-1, nothingWaits, 1 << 30), 0)
      << "a walk never told to stop is whole";
  EXPECT_GT(never, 0) << "it asked";
}

TEST(TileSelection, ABudgetRaisesTheToleranceAndKeepsEveryVisibleTile) {
  auto hand = importMesh(testing::cgalMeshPath("hand.off"));
  ASSERT_TRUE(hand.isOk());
  auto doc = Document::create(*hand, {.maxLevel = 4});
  ASSERT_TRUE(doc.isOk());
  Model m = model("hand", std::move(*doc));
  TileCatalogue catalogue(m.doc);
  std::mt19937 rng(5);
  const View view = randomView(m, rng, 1920, 1080);
  auto free = selectTiles(view, catalogue);
  ASSERT_TRUE(free.isOk());
  auto tight = selectTiles(view, catalogue, free->triangles / 4);
  ASSERT_TRUE(tight.isOk());
  EXPECT_LE(tight->triangles, free->triangles / 4);
  EXPECT_GT(tight->tolerancePixels, view.tolerancePixels);
  // The same surface covered: every base face still shown.
  std::set<uint64_t> faces;
  for (const SelectedTile& t : tight->tiles)
    for (const FaceId& f : catalogue.tree().facesShown(t.key)) faces.insert(f.index() >> (2 * f.level()));
  EXPECT_EQ(faces.size(), m.doc.counts().faces(0));
  // A bad view is refused by name.
  View bad = view;
  bad.tolerancePixels = 0;
  EXPECT_NE(selectTiles(bad, catalogue).status().message().find("tolerance"), std::string::npos);
}

}  // namespace
}  // namespace tessera
