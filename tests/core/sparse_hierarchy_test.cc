// The sparse forest and its incremental updates (core/hierarchy/sparse_hierarchy.h):
// incidence arithmetic against uniform topology, agreement with the dense
// reference evaluator to 1e-9 after every step of long random histories,
// dirty sets that cover every changed displayed limit, recompute counts
// independent of mesh size, and sparseness.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/document/document.h"
#include "core/document/document_evaluator.h"
#include "core/hierarchy/incidence.h"
#include "core/loop/limit.h"
#include "core/loop/loop_refiner.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

using testing::TestMesh;

TEST(Incidence, TheIncidentFaceHoldsTheElementAtEveryLevel) {
  for (const TestMesh& mesh : {testing::icosahedron(), testing::openGrid(4, 3),
                               testing::withRandomFlips(testing::torus(6, 5), 8, 3)}) {
    auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = 3});
    ASSERT_TRUE(refiner.isOk());
    const Level& base = refiner->level(0);
    LevelCounts counts(base.numVertices, base.numEdges(), base.numFaces(), 3);
    for (int l = 0; l <= 3; ++l) {
      const Level& level = refiner->level(l);
      for (Index v = 0; v < level.numVertices; ++v) {
        const FaceId f = incidentFace(base, counts, VertexId(l, v));
        const auto fv = level.triangleVertices(f.index());
        ASSERT_TRUE(std::find(fv.begin(), fv.end(), v) != fv.end()) << mesh.name << " v" << l << ":" << v;
      }
      for (Index e = 0; e < level.numEdges(); ++e) {
        const FaceId f = incidentFace(base, counts, EdgeId(l, e));
        const auto fe = level.triangleEdges(f.index());
        ASSERT_TRUE(std::find(fe.begin(), fe.end(), e) != fe.end()) << mesh.name << " e" << l << ":" << e;
      }
    }
  }
}

// Every present vertex of every level equals the dense reference; every
// displayed limit equals the dense limit at that level.
void expectMatchesDense(const Document& doc, const std::string& where) {
  const SparseHierarchy& sparse = doc.hierarchy();
  auto dense = evaluateDocument(doc.baseTopology(), doc.basePoints(), doc.options().loop, doc.edits(),
                                sparse.numLevels() - 1);
  ASSERT_TRUE(dense.isOk()) << dense.status().message();
  double worstPoint = 0.0, worstLimit = 0.0, worstNormal = 0.0;
  for (int l = 0; l < sparse.numLevels(); ++l) {
    const SparseLevel& level = sparse.level(l);
    const auto points = sparse.points(l);
    for (Index v = 0; v < level.mesh.numVertices; ++v) {
      const uint64_t id = level.vertexIds[v];
      const double err = (points[v] - dense->points[l][id]).norm();
      if (err > 1e-9 && worstPoint <= 1e-9) {
        ADD_FAILURE() << where << ": first bad point v" << l << ":" << id << " local " << v << " complete "
                      << int(level.complete[v]) << " err " << err << " displayed " << sparse.isDisplayed(l, v)
                      << " predicted err " << (sparse.predicted(l)[v] - dense->predicted[l][id]).norm();
      }
      worstPoint = std::max(worstPoint, err);
      if (!level.isComplete(v)) continue;
      const LimitFrame ref = limitFrame(dense->levels[l], static_cast<Index>(id), dense->points[l],
                                        doc.options().loop.creaseMethod);
      worstLimit = std::max(worstLimit, (sparse.limitPosition(l, v) - ref.position).norm());
      worstNormal = std::max(worstNormal, (sparse.limitNormal(l, v) - ref.normal()).norm());
    }
  }
  EXPECT_LE(worstPoint, 1e-9) << where;
  EXPECT_LE(worstLimit, 1e-9) << where;
  EXPECT_LE(worstNormal, 1e-9) << where;
}

// Limits of complete vertices, keyed by (level, canonical vertex).
std::map<std::pair<int, uint64_t>, std::pair<Vec3, Vec3>> completeLimits(const SparseHierarchy& sparse) {
  std::map<std::pair<int, uint64_t>, std::pair<Vec3, Vec3>> out;
  for (int l = 0; l < sparse.numLevels(); ++l) {
    for (Index v = 0; v < sparse.level(l).mesh.numVertices; ++v) {
      if (sparse.level(l).isComplete(v)) {
        out[{l, sparse.level(l).vertexIds[v]}] = {sparse.limitPosition(l, v), sparse.limitNormal(l, v)};
      }
    }
  }
  return out;
}

// Every complete vertex whose limit changed is in the dirty set.
void expectDirtySetCovers(const Document& doc,
                          const std::map<std::pair<int, uint64_t>, std::pair<Vec3, Vec3>>& before,
                          const std::string& where) {
  const SparseHierarchy& sparse = doc.hierarchy();
  const DirtySet& dirty = doc.lastUpdate();
  if (dirty.grownFromLevel >= 0) return;  // growth rebuilds the levels below it
  for (int l = 0; l < sparse.numLevels(); ++l) {
    const SparseLevel& level = sparse.level(l);
    for (Index v = 0; v < level.mesh.numVertices; ++v) {
      if (!level.isComplete(v)) continue;
      auto it = before.find({l, level.vertexIds[v]});
      ASSERT_TRUE(it != before.end()) << where;
      if (sparse.limitPosition(l, v) == it->second.first && sparse.limitNormal(l, v) == it->second.second)
        continue;
      const VertexId id(l, level.vertexIds[v]);
      ASSERT_TRUE(std::binary_search(dirty.limits.begin(), dirty.limits.end(), id))
          << where << ": the limit of " << id.toString() << " changed but is not in the dirty set";
      // So are the displayed leaves it is a corner of, and their roots.
      for (Index f : level.mesh.ringFacesOf(v)) {
        if (f < 0 || !sparse.isLeaf(l, f)) continue;
        const FaceId leaf(l, level.faceIds[f]);
        ASSERT_TRUE(std::binary_search(dirty.leaves.begin(), dirty.leaves.end(), leaf))
            << where << " " << leaf.toString();
        ASSERT_TRUE(std::binary_search(dirty.baseFaces.begin(), dirty.baseFaces.end(),
                                       doc.counts().baseFace(leaf).index()));
      }
    }
  }
}

// Finer edits at an interpolating vertex are refused (interpolation_conflicts.h).
bool refusedNextToInterpolation(const Expected<EditId>& id) {
  return !id.isOk() && id.status().message().find("conflicts with interpolating vertex") != std::string::npos;
}

struct PropertyCase {
  TestMesh mesh;
  LoopOptions options;
  int uniformLevel;
  int steps;
  // When > 0: before every this many steps, a tessellation's growth (as a
  // view's) at a few random faces of a random level, checked as a step.
  int growEvery = 0;
};

void runRandomHistory(const PropertyCase& c, uint32_t seed) {
  const int maxLevel = 4;
  auto doc = Document::create(c.mesh.topology, c.mesh.points,
                              {.loop = c.options, .maxLevel = maxLevel, .uniformLevel = c.uniformLevel});
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  std::mt19937 rng(seed);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto pick = [&](uint64_t n) { return std::uniform_int_distribution<uint64_t>(0, n - 1)(rng); };
  // Edits stay near a few spots, so that later edits land on refined areas.
  std::vector<EditId> made;
  for (int step = 0; step < c.steps; ++step) {
    if (c.growEvery > 0 && step % c.growEvery == 0) {
      const int at = 1 + static_cast<int>(pick(maxLevel));
      std::vector<FaceId> faces;
      for (int k = 0; k < 3; ++k) faces.push_back(FaceId(at, pick(doc->counts().faces(at))));
      const auto limitsBefore = completeLimits(doc->hierarchy());
      doc->refineHierarchy(faces);
      const std::string where =
          c.mesh.name + " step " + std::to_string(step) + " (growth at level " + std::to_string(at) + ")";
      expectMatchesDense(*doc, where);
      // Growth changes no value: every limit held before is held after, equal.
      for (const auto& [key, limit] : completeLimits(doc->hierarchy())) {
        auto was = limitsBefore.find(key);
        if (was == limitsBefore.end()) continue;
        ASSERT_EQ(was->second.first, limit.first) << where << " v" << key.first << ":" << key.second;
        ASSERT_EQ(was->second.second, limit.second) << where << " v" << key.first << ":" << key.second;
      }
      if (::testing::Test::HasFailure()) return;
    }
    const int level = static_cast<int>(pick(maxLevel + 1));
    const uint64_t spot = pick(std::min<uint64_t>(doc->counts().vertices(0), 3));
    // A vertex descended from one of the few spots, or on an edge near one.
    const uint64_t vertex = pick(10) < 7 ? spot : pick(doc->counts().vertices(level));
    const auto before = completeLimits(doc->hierarchy());
    const int op = static_cast<int>(pick(100));
    std::string what;
    if (op < 40) {
      const VertexId v(level, vertex);
      auto id = doc->moveBy(std::span(&v, 1), Vec3(uniform(-.1, .1), uniform(-.1, .1), uniform(-.1, .1)));
      if (refusedNextToInterpolation(id)) continue;
      ASSERT_TRUE(id.isOk()) << id.status().message();
      made.push_back(*id);
      what = "move " + v.toString();
    } else if (op < 50) {
      const VertexId v(level, vertex);
      auto id = doc->moveToLimit(std::span(&v, 1), Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)));
      if (refusedNextToInterpolation(id)) continue;
      ASSERT_TRUE(id.isOk()) << id.status().message();
      made.push_back(*id);
      what = "drag " + v.toString();
    } else if (op < 62) {
      const EdgeId e(level, pick(doc->counts().edges(level)));
      const float sharpness = std::array<float, 5>{0.0f, 0.5f, 1.5f, 3.0f, kSharpnessInfinite}[pick(5)];
      auto id = doc->setEdgeSharpness(e, sharpness);
      if (!id.isOk()) continue;  // boundary edges are refused
      made.push_back(*id);
      what = "crease " + e.toString();
    } else if (op < 68) {
      const VertexId v(level, vertex);
      auto id = doc->setVertexSharpness(v, std::array<float, 3>{0.0f, 1.5f, kSharpnessInfinite}[pick(3)]);
      if (refusedNextToInterpolation(id)) continue;
      ASSERT_TRUE(id.isOk()) << id.status().message();
      made.push_back(*id);
      what = "corner " + v.toString();
    } else if (op < 76) {
      // An interpolating vertex (or its end; docs/INTERPOLATION.md); refused where its
      // rule admits no ghost ring, at the deepest level, or next to finer edits.
      const VertexId v(std::min(level, maxLevel - 1),
                       vertex % doc->counts().vertices(std::min(level, maxLevel - 1)));
      const bool on = pick(4) != 0;
      auto id = doc->setInterpolation(v, on, std::array<double, 3>{0.5, 1.0, 3.0}[pick(3)]);
      if (!id.isOk()) continue;
      made.push_back(*id);
      what = (on ? "interpolate " : "stop interpolating ") + v.toString();
    } else if (!made.empty()) {
      const EditId id = made[pick(made.size())];
      Status s = op < 86 ? doc->undo(id) : (op < 97 ? doc->redo(id) : doc->remove(id));
      if (!s.isOk()) continue;  // undoing an undone edit, or one removed
      what = (op < 86 ? "undo " : op < 97 ? "redo " : "remove ") + id.toString();
    } else {
      continue;
    }
    const std::string where = c.mesh.name + " step " + std::to_string(step) + " (" + what + ")";
    expectMatchesDense(*doc, where);
    expectDirtySetCovers(*doc, before, where);
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(SparseHierarchy, RandomHistoriesMatchTheDenseReferenceAtEveryStep) {
  LoopOptions chaikin;
  chaikin.creaseMethod = CreaseMethod::kChaikin;
  LoopOptions corners;
  corners.boundary = BoundaryInterpolation::kEdgeAndCorner;
  const std::vector<PropertyCase> cases = {
      {testing::icosahedron(), {}, 0, 500},
      {testing::withRandomTags(testing::torus(6, 4), 0.2, 0.1, 7), chaikin, 1, 500},
      {testing::openGrid(5, 4), corners, 0, 500},
      {testing::withRandomTags(testing::diskWithPole(9), 0.3, 0.2, 11), {}, 0, 400},
      {testing::withRandomFlips(testing::bipyramid(7), 3, 5), {}, 2, 300},
  };
  uint32_t seed = 1;
  for (const PropertyCase& c : cases) {
    SCOPED_TRACE(c.mesh.name);
    runRandomHistory(c, seed++);
    if (HasFailure()) return;
  }
}

// A view grows the hierarchy wherever its camera needs tiles, between
// edits; levels grow in place, keeping the points and limits of the
// vertices they held (sparse_hierarchy.cc, growFrom). After every growth
// and every edit the state equals the dense reference, and no limit held
// before a growth moved.
TEST(SparseHierarchy, GrowthBetweenEditsKeepsEveryValue) {
  LoopOptions chaikin;
  chaikin.creaseMethod = CreaseMethod::kChaikin;
  const std::vector<PropertyCase> cases = {
      {testing::withRandomTags(testing::torus(6, 4), 0.2, 0.1, 17), chaikin, 0, 200, 3},
      {testing::withRandomTags(testing::diskWithPole(9), 0.3, 0.2, 19), {}, 1, 200, 2},
      {testing::openGrid(5, 4), {}, 0, 150, 2},
  };
  uint32_t seed = 101;
  for (const PropertyCase& c : cases) {
    SCOPED_TRACE(c.mesh.name);
    runRandomHistory(c, seed++);
    if (HasFailure()) return;
  }
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// §4.2: the work of an edit follows its footprint, not the mesh. The same
// edit on two tori ten times apart in size recomputes the same number of
// points and limits, at every level.
TEST(SparseHierarchy, RecomputeCountsDoNotGrowWithMeshSize) {
  const testing::TestMesh small = testing::torus(10, 8), large = testing::torus(32, 25);
  ASSERT_GE(large.topology.triangles.size(), 10 * small.topology.triangles.size());
  for (int level = 0; level <= 3; ++level) {
    std::vector<int64_t> points, limits;
    int64_t largeVertices = 0;
    for (const testing::TestMesh* mesh : {&small, &large}) {
      auto doc = Document::create(mesh->topology, mesh->points, {.maxLevel = 4, .uniformLevel = 3});
      ASSERT_TRUE(doc.isOk());
      const VertexId v(level, 0);
      ASSERT_TRUE(doc->moveBy(std::span(&v, 1), Vec3(0.01, 0.02, 0.03)).isOk());
      const DirtySet& dirty = doc->lastUpdate();
      EXPECT_EQ(dirty.grownFromLevel, -1);
      points.push_back(dirty.pointsRecomputed);
      limits.push_back(dirty.limitsRecomputed);
      largeVertices = doc->hierarchy().stats().vertices;
    }
    SCOPED_TRACE("edit at level " + std::to_string(level));
    EXPECT_EQ(points[0], points[1]);
    EXPECT_EQ(limits[0], limits[1]);
    EXPECT_GT(points[0], 0);
    EXPECT_LT(points[1] * 10, largeVertices);
    std::printf("edit at level %d: %lld points, %lld limits recomputed (of %lld points held)\n", level,
                static_cast<long long>(points[1]), static_cast<long long>(limits[1]),
                static_cast<long long>(largeVertices));
  }
}

// §4.1: one deep edit refines only around itself. A level-6 edit on a base
// mesh of 160 faces holds a few hundred level-6 vertices, not the 655k of
// the uniform level, and every level keeps the padding its stencils need.
TEST(SparseHierarchy, ADeepEditRefinesOnlyAroundItself) {
  const testing::TestMesh mesh = testing::torus(10, 8);
  auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = 6, .uniformLevel = 0});
  ASSERT_TRUE(doc.isOk());
  const VertexId v(6, 5);
  ASSERT_TRUE(doc->moveToLimit(std::span(&v, 1), Vec3(1.5, 0.1, 0.4)).isOk());
  EXPECT_EQ(doc->lastUpdate().grownFromLevel, 0);
  const HierarchyStats stats = doc->hierarchy().stats();
  ASSERT_EQ(stats.levels.size(), 7u);
  for (int l = 1; l <= 6; ++l) {
    EXPECT_LT(stats.levels[l].vertices * 50,
              static_cast<int64_t>(doc->counts().vertices(l)) * (l >= 3 ? 1 : 50))
        << "level " << l;
    EXPECT_GT(stats.levels[l].leaves, 0) << "level " << l;
  }
  std::printf("deep edit: %lld points held, %lld displayed, %.1f bytes per displayed vertex\n",
              static_cast<long long>(stats.vertices), static_cast<long long>(stats.displayedVertices),
              static_cast<double>(stats.bytes) / static_cast<double>(stats.displayedVertices));
  // Its leaves tile the torus: every base face is a leaf or has leaves below.
  int64_t leafArea = 0;  // in level-6 triangles
  for (int l = 0; l <= 6; ++l) leafArea += stats.levels[l].leaves << (2 * (6 - l));
  EXPECT_EQ(leafArea, static_cast<int64_t>(doc->counts().faces(6)));
}

}  // namespace
}  // namespace tessera
