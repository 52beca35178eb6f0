// Adaptive crack-free tessellation and regions:
// watertight, oriented, non-degenerate tessellations whose every vertex is
// the true limit, the quality of a single deep edit's tessellation, and
// region change sets equal to a full diff.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/document/document.h"
#include "core/document/document_evaluator.h"
#include "core/loop/exact_limit.h"
#include "core/loop/limit.h"
#include "core/mesh/sharpness.h"
#include "core/render/surface_distance.h"
#include "core/tessellation/tessellation.h"
#include "support/procedural_meshes.h"
#include "support/region_checks.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using testing::TestMesh;

// Random moves and tags around a few spots, at levels 0..maxLevel.
void randomEdits(Document& doc, int count, uint32_t seed, float creaseSharpness) {
  std::mt19937 rng(seed);
  auto pick = [&](uint64_t n) { return std::uniform_int_distribution<uint64_t>(0, n - 1)(rng); };
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  for (int i = 0; i < count; ++i) {
    const int level = static_cast<int>(pick(doc.options().maxLevel + 1));
    const uint64_t vertex = pick(10) < 6 ? pick(std::min<uint64_t>(3, doc.counts().vertices(0)))
                                         : pick(doc.counts().vertices(level));
    if (creaseSharpness < 0 || pick(10) < 8) {
      const VertexId v(level, vertex);
      ASSERT_TRUE(
          doc.moveBy(std::span(&v, 1), Vec3(uniform(-.1, .1), uniform(-.1, .1), uniform(-.1, .1))).isOk());
    } else {
      (void)doc.setEdgeSharpness(EdgeId(level, pick(doc.counts().edges(level))), creaseSharpness);
    }
  }
}

struct Check {
  bool closed;
  double diagonal;
};

// Watertight (closed) or boundary-preserving (open), consistently oriented,
// no T-junctions (every edge of the union is shared by two triangles, or is
// on the boundary), no degenerate triangles, and every vertex its limit.
void expectSoundTessellation(const Document& doc, const Tessellation& t, const std::string& where) {
  const SparseHierarchy& h = doc.hierarchy();
  const int finest = doc.options().maxLevel;
  auto dense =
      evaluateDocument(doc.baseTopology(), doc.basePoints(), doc.options().loop, doc.edits(), finest);
  ASSERT_TRUE(dense.isOk());
  std::map<std::pair<uint64_t, uint64_t>, int> directed;
  double worstLimit = 0.0;
  int degenerate = 0;
  for (const auto& [id, mesh] : t.regions()) {
    for (const auto& tri : mesh.triangles) {
      uint64_t v[3];
      for (int k = 0; k < 3; ++k) v[k] = VertexId::fromPacked(mesh.vertexIds[tri[k]]).index();
      ASSERT_TRUE(v[0] != v[1] && v[1] != v[2] && v[2] != v[0]) << where << ": a triangle repeats a vertex";
      const Vec3 n = (mesh.positions[tri[1]] - mesh.positions[tri[0]]) %
                     (mesh.positions[tri[2]] - mesh.positions[tri[0]]);
      // Twice the area, against the square of a typical edge of the finest level.
      degenerate += n.norm() < 1e-14 ? 1 : 0;
      for (int k = 0; k < 3; ++k) ++directed[{v[k], v[(k + 1) % 3]}];
    }
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      // OpenSubdiv's limit at the document's finest level: the true limit
      // wherever semi-sharp features decay by then (their limit masks at a
      // level still count them as sharp), and what the tessellation shows
      // where they do not (tessellation.h).
      const uint64_t index = VertexId::fromPacked(mesh.vertexIds[i]).index();
      const Vec3 truth =
          limitFrame(dense->levels[finest], static_cast<Index>(index), dense->points[finest]).position;
      const double err = (mesh.positions[i] - truth).norm();
      if (err > 1e-9 && worstLimit <= 1e-9) {
        std::string info;
        for (int l = 0; l < std::min(h.numLevels(), finest + 1); ++l) {
          const Index local = h.level(l).findVertex(index);
          info += " L" + std::to_string(l) +
                  (local < 0 ? ":absent" : (h.level(l).isComplete(local) ? ":complete" : ":partial"));
          if (local >= 0 && h.level(l).isComplete(local)) {
            info += " rule " + std::to_string(int(h.level(l).mesh.vertexRules[local]));
            const Vec3 d = limitFrame(dense->levels[l], static_cast<Index>(index), dense->points[l]).position;
            info += "(to truth " + std::to_string((d - truth).norm()) + ")";
          }
        }
        ADD_FAILURE() << where << " v" << index << info;
      }
      worstLimit = std::max(worstLimit, err);
    }
  }
  EXPECT_EQ(degenerate, 0) << where;
  EXPECT_LE(worstLimit, 1e-9) << where << ": a vertex is not its true limit";
  bool closed = true;
  const Level& base = h.level(0).mesh;
  for (Index e = 0; e < base.numEdges(); ++e) closed = closed && !base.isBoundaryEdge(e);
  // An open edge must join two vertices of the base mesh's boundary.
  auto onBoundary = [&](uint64_t index) {
    for (int l = 0; l < h.numLevels(); ++l) {
      const Index local = h.level(l).findVertex(index);
      if (local >= 0 && h.level(l).isComplete(local)) return h.level(l).mesh.isBoundaryVertex(local);
    }
    return false;
  };
  int open = 0;
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << where << ": a directed edge is used twice (orientation or non-manifold)";
    if (directed.count({edge.second, edge.first}) != 0) continue;
    ++open;
    ASSERT_FALSE(closed) << where << ": open edge v" << edge.first << "-v" << edge.second
                         << " (crack or T-junction)";
    ASSERT_TRUE(onBoundary(edge.first) && onBoundary(edge.second))
        << where << ": open edge v" << edge.first << "-v" << edge.second << " inside the surface";
  }
  if (!closed) {
    EXPECT_GT(open, 0) << where;
  }
}

const LodProfile kProfile{
    .baseLevel = 1, .maxLevel = 4, .angleThresholdDegrees = 12, .triangleBudget = 10'000'000};

TEST(Tessellation, IsWatertightOrientedAndExactAfterRandomEdits) {
  LoopOptions corners;
  corners.boundary = BoundaryInterpolation::kEdgeAndCorner;
  // Every displayed vertex is the limit of the document's finest level,
  // with or without tags (semi-sharp creases are evaluated past their
  // decay, tessellation.h). (crease < 0: moves only.)
  struct Case {
    TestMesh mesh;
    LoopOptions options;
    float crease;
  };
  const std::vector<Case> cases = {
      {testing::icosahedron(), {}, -1},
      {testing::icosahedron(), {}, kSharpnessInfinite},
      {testing::icosahedron(), {}, 2.0f},
      {testing::withRandomTags(testing::torus(8, 6), 0.15, 0.05, 3), {}, 1.5f},
      {testing::openGrid(5, 4), corners, -1},
      {testing::openGrid(5, 4), {}, kSharpnessInfinite},
      {testing::withRandomTags(testing::diskWithPole(9), 0.3, 0.2, 11), {}, kSharpnessInfinite},
      {testing::withRandomFlips(testing::torus(6, 5), 6, 2), {}, -1},
  };
  uint32_t seed = 5;
  for (const auto& [mesh, options, crease] : cases) {
    for (int round = 0; round < 3; ++round) {
      auto doc = Document::create(mesh.topology, mesh.points, {.loop = options, .maxLevel = 4});
      ASSERT_TRUE(doc.isOk());
      randomEdits(*doc, 4 + 6 * round, seed++, crease);
      for (bool fidelity : {false, true}) {
        LodProfile profile = kProfile;
        profile.fidelity = fidelity;
        auto t = Tessellation::build(*doc, profile);
        ASSERT_TRUE(t.isOk()) << t.status().message();
        expectSoundTessellation(
            *doc, *t, mesh.name + " crease " + std::to_string(crease) + " round " + std::to_string(round));
        if (HasFailure()) return;
      }
    }
  }
}

// Interpolating vertices (docs/INTERPOLATION.md) at levels 0..2 among random moves
// (those next to them refused): the tessellation stays watertight and
// oriented, and every displayed vertex is its true limit at the finest level.
TEST(Tessellation, IsWatertightAndExactWithInterpolatingVertices) {
  const std::vector<TestMesh> meshes = {testing::withJitter(testing::icosahedron(), 0.1, 2),
                                        testing::withJitter(testing::torus(8, 6), 0.05, 4),
                                        testing::withJitter(testing::openGrid(5, 4), 0.05, 6)};
  uint32_t seed = 40;
  for (const TestMesh& mesh : meshes) {
    auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = 4});
    ASSERT_TRUE(doc.isOk());
    std::mt19937 rng(seed++);
    auto pick = [&](uint64_t n) { return std::uniform_int_distribution<uint64_t>(0, n - 1)(rng); };
    int tagged = 0;
    for (int i = 0; i < 24; ++i) {
      const int level = static_cast<int>(pick(3));
      const VertexId v(level, pick(doc->counts().vertices(level)));
      if (i % 3 == 0) {
        tagged +=
            doc->setInterpolation(v, true, std::array<double, 3>{0.5, 1.0, 4.0}[pick(3)]).isOk() ? 1 : 0;
      } else {
        (void)doc->moveBy(std::span(&v, 1), Vec3(0.03 * (pick(7) - 3.0), 0.02, -0.04));
      }
    }
    EXPECT_GE(tagged, 3) << mesh.name;
    auto t = Tessellation::build(*doc, kProfile);
    ASSERT_TRUE(t.isOk()) << t.status().message();
    expectSoundTessellation(*doc, *t, mesh.name + " with interpolating vertices");
    if (HasFailure()) return;
  }
}

// docs/LIMITS.md: the normals a viewer shades with are the exact limit
// normals (exactVertexLimit, checked against Bfr in bfr_limit_test.cc), not
// the masks of the level's rules. Darts, crease sectors of any size,
// corners and semi-sharp features are displayed; each displayed normal
// must be one of its vertex's exact sector normals at the finest level.
TEST(Tessellation, NormalsAreTheExactLimitNormals) {
  for (const LoopOptions& options : {LoopOptions{}, LoopOptions{.creaseMethod = CreaseMethod::kChaikin}}) {
    const TestMesh mesh =
        testing::withRandomTags(testing::withJitter(testing::torus(8, 6), 0.05, 9), 0.25, 0.1, 61);
    auto doc = Document::create(mesh.topology, mesh.points, {.loop = options, .maxLevel = 3});
    ASSERT_TRUE(doc.isOk());
    randomEdits(*doc, 6, 62, 2.5f);
    auto t = Tessellation::build(
        *doc,
        LodProfile{.baseLevel = 1, .maxLevel = 3, .angleThresholdDegrees = 12, .triangleBudget = 10'000'000});
    ASSERT_TRUE(t.isOk()) << t.status().message();
    const int finest = doc->options().maxLevel;
    auto dense = evaluateDocument(doc->baseTopology(), doc->basePoints(), options, doc->edits(), finest);
    ASSERT_TRUE(dense.isOk());
    const Level& level = dense->levels[finest];
    int displayed = 0, nonSmooth = 0, semiSharp = 0;
    double worst = 0.0;
    for (const auto& [id, region] : t->regions()) {
      for (size_t i = 0; i < region.positions.size(); ++i) {
        const auto v = static_cast<Index>(VertexId::fromPacked(region.vertexIds[i]).index());
        const VertexLimit exact = exactVertexLimit(level, v, dense->points[finest], options.creaseMethod);
        double best = std::atan2((region.normals[i] % exact.frame.normal()).norm(),
                                 dot(region.normals[i], exact.frame.normal()));
        for (const LimitSector& side : exact.others) {
          best = std::min(best, std::atan2((region.normals[i] % side.normal).norm(),
                                           dot(region.normals[i], side.normal)));
        }
        worst = std::max(worst, best);
        ++displayed;
        nonSmooth += level.vertexRules[v] != VertexRule::kSmooth ? 1 : 0;
        bool decaying = isSemiSharp(level.vertexSharpness[v]);
        for (Index e : level.ringEdgesOf(v)) decaying = decaying || isSemiSharp(level.edgeSharpness[e]);
        semiSharp += decaying ? 1 : 0;
      }
    }
    EXPECT_LE(worst, 1e-9) << "a displayed normal is none of its vertex's exact limit normals";
    EXPECT_GT(nonSmooth, 50) << "the tags must put creases, darts and corners on screen";
    EXPECT_GT(semiSharp, 5) << "semi-sharp features must still be decaying at the finest level";
    std::printf(
        "[ measured ] %s decay: %d displayed vertices, %d not smooth, %d with features still decaying, worst "
        "%.2e rad\n",
        options.creaseMethod == CreaseMethod::kChaikin ? "Chaikin" : "uniform", displayed, nonSmooth,
        semiSharp, worst);
  }
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return (p - closestOnTriangle(p, a, b, c)).norm();
}

// §2 quality: one level-4 edit on a 768-triangle torus. The adaptive
// tessellation needs at least 20x fewer triangles than uniform level 4,
// its vertices are vertices of the uniform level-4 limit surface, and that
// surface stays within 1% of the bounding-box diagonal of it.
TEST(Tessellation, ASingleDeepEditNeedsFarFewerTrianglesThanUniform) {
  const TestMesh mesh = testing::torus(24, 16);
  auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = 4});
  ASSERT_TRUE(doc.isOk());
  const VertexId v(4, 7);
  ASSERT_TRUE(doc->moveBy(std::span(&v, 1), Vec3(0, 0, 0.05)).isOk());
  auto t = Tessellation::build(*doc, {.baseLevel = 0, .maxLevel = 4, .angleThresholdDegrees = 30});
  ASSERT_TRUE(t.isOk()) << t.status().message();
  const int64_t uniformTriangles = static_cast<int64_t>(doc->counts().faces(4));
  EXPECT_LE(t->numTriangles() * 20, uniformTriangles) << t->numTriangles() << " triangles";

  auto dense = evaluateDocument(doc->baseTopology(), doc->basePoints(), {}, doc->edits(), 4);
  ASSERT_TRUE(dense.isOk());
  std::vector<Vec3> limit(dense->levels[4].numVertices), normals(limit.size());
  computeLimit(dense->levels[4], dense->points[4], limit, normals);
  Vec3 lo = limit[0], hi = limit[0];
  for (const Vec3& p : limit) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  }
  const double diagonal = (hi - lo).norm();
  const SurfaceMesh surface = t->surface();
  double onUniform = 0.0;
  for (const auto& [id, region] : t->regions()) {
    for (size_t i = 0; i < region.positions.size(); ++i) {
      const uint64_t index = VertexId::fromPacked(region.vertexIds[i]).index();
      onUniform = std::max(onUniform, (region.positions[i] - limit[index]).norm());
    }
  }
  // Every 7th uniform vertex plus every one near the edit, against all
  // adaptive triangles.
  double worst = 0.0;
  const Vec3 editAt = limit[v.index()];
  for (size_t i = 0; i < limit.size(); ++i) {
    if (i % 7 != 0 && (limit[i] - editAt).norm() > 0.3) continue;
    double best = 1e300;
    for (const auto& tri : surface.triangles) {
      best = std::min(best, pointTriangleDistance(limit[i], surface.positions[tri[0]],
                                                  surface.positions[tri[1]], surface.positions[tri[2]]));
    }
    worst = std::max(worst, best);
  }
  EXPECT_LE(onUniform, 1e-9 * diagonal);
  EXPECT_LE(worst, 0.01 * diagonal);
  std::printf(
      "single level-4 edit: %lld adaptive triangles vs %lld uniform (%.1fx fewer); uniform surface within "
      "%.5f of the diagonal\n",
      static_cast<long long>(t->numTriangles()), static_cast<long long>(uniformTriangles),
      static_cast<double>(uniformTriangles) / static_cast<double>(t->numTriangles()), worst / diagonal);
}

// An updated tessellation holds what a fresh build holds
// (support/region_checks.h).
using testing::expectSameRegions;

// §3: after every update the reported regions are exactly those whose
// triangles differ in a full diff against a fresh tessellation. An update
// follows 1..maxBatch random edits, given the union of their changed limits
// (as a server batching queued edits does).
void expectChangesEqualAFullDiff(int maxBatch, uint32_t seed) {
  struct Case {
    TestMesh mesh;
    LodProfile profile;
  };
  const std::vector<Case> cases = {
      {testing::withRandomTags(testing::torus(8, 6), 0.1, 0.05, 9),
       {.baseLevel = 1, .maxLevel = 6, .angleThresholdDegrees = 12}},
      {testing::icosahedron(),
       {.baseLevel = 2, .maxLevel = 6, .angleThresholdDegrees = 20, .fidelity = true}},
      {testing::openGrid(4, 4), {.baseLevel = 0, .maxLevel = 5, .angleThresholdDegrees = 8}},
  };
  for (const Case& c : cases) {
    auto doc = Document::create(c.mesh.topology, c.mesh.points, {.maxLevel = 6, .uniformLevel = 1});
    ASSERT_TRUE(doc.isOk());
    auto t = Tessellation::build(*doc, c.profile);
    ASSERT_TRUE(t.isOk()) << t.status().message();
    std::mt19937 rng(seed++);
    auto pick = [&](uint64_t n) { return std::uniform_int_distribution<uint64_t>(0, n - 1)(rng); };
    int rebuilt = 0, incremental = 0, moved = 0;
    for (int step = 0; step < 60; ++step) {
      const std::map<uint64_t, RegionMesh> before = t->regions();
      std::vector<VertexId> limits;
      const int batch = 1 + static_cast<int>(pick(static_cast<uint64_t>(maxBatch)));
      for (int e = 0; e < batch; ++e) {
        const int level = static_cast<int>(pick(7));
        const VertexId v(level, pick(std::min<uint64_t>(doc->counts().vertices(level), 40)));
        const int op = static_cast<int>(pick(10));
        if (op < 7) {
          ASSERT_TRUE(doc->moveBy(std::span(&v, 1), Vec3(0.02 * (op - 3), 0.03, -0.01)).isOk());
        } else if (op < 9) {
          const EdgeId edge(level, pick(doc->counts().edges(level)));
          if (!doc->setEdgeSharpness(edge, op == 7 ? 1.5f : kSharpnessInfinite).isOk()) continue;
        } else if (!doc->edits().empty()) {
          ASSERT_TRUE(doc->remove(doc->edits()[pick(doc->edits().size())].id).isOk());
        } else {
          continue;
        }
        limits.insert(limits.end(), doc->lastUpdate().limits.begin(), doc->lastUpdate().limits.end());
      }
      std::sort(limits.begin(), limits.end());
      limits.erase(std::unique(limits.begin(), limits.end()), limits.end());
      auto changes = t->update(*doc, limits);
      ASSERT_TRUE(changes.isOk()) << changes.status().message();
      (changes->rebuilt ? rebuilt : incremental) += 1;
      auto fresh = Tessellation::build(*doc, c.profile);
      ASSERT_TRUE(fresh.isOk());
      std::vector<uint64_t> changed, relaid, removed;
      for (const auto& [id, mesh] : fresh->regions()) {
        auto old = before.find(id);
        if (old == before.end() || old->second.triangles != mesh.triangles ||
            old->second.positions != mesh.positions || old->second.normals != mesh.normals ||
            old->second.vertexIds != mesh.vertexIds) {
          changed.push_back(id);
        }
        if (old == before.end() || old->second.triangles != mesh.triangles ||
            old->second.vertexIds != mesh.vertexIds) {
          relaid.push_back(id);
        }
      }
      for (const auto& [id, mesh] : before) {
        if (fresh->regions().count(id) == 0) removed.push_back(id);
      }
      const std::string where = c.mesh.name + " step " + std::to_string(step);
      ASSERT_EQ(changes->changed, changed) << where;
      ASSERT_EQ(changes->relaid, relaid) << where;  // the rest keep their layout: deltas omit their ids
      moved += static_cast<int>(changed.size() - relaid.size());
      ASSERT_EQ(changes->removed, removed) << where;
      ASSERT_EQ(t->regions().size(), fresh->regions().size()) << where;
      // And what the updated regions hold is what a fresh build holds.
      expectSameRegions(*t, *fresh, where);
      if (::testing::Test::HasFatalFailure()) return;
    }
    std::printf(
        "%s, up to %d edits per update: %d incremental updates, %d rebuilds (hierarchy growth), %d regions "
        "only moved\n",
        c.mesh.name.c_str(), maxBatch, incremental, rebuilt, moved);
    EXPECT_GT(incremental, 0);
    EXPECT_GT(moved, 0);
  }
}

TEST(Tessellation, RegionChangesEqualAFullDiff) {
  expectChangesEqualAFullDiff(1, 21);
}

TEST(Tessellation, RegionChangesAfterSeveralEditsEqualAFullDiff) {
  expectChangesEqualAFullDiff(5, 77);
}

// What a server does to the demo document: the creased cube (infinitely
// sharp, semi-sharp and one-level creases, a corner) under the load
// tester's profile, with offsets of level-2 vertices, undo and redo, new
// creases and corners, 1..6 at a time; every update's regions equal a
// fresh build's.
TEST(Tessellation, TheCreasedCubeUnderMixedEditsMatchesAFreshBuild) {
  auto mesh = testing::creasedCube();
  ASSERT_TRUE(mesh.isOk()) << mesh.status().message();
  auto doc = Document::create(*mesh, {.maxLevel = 5});
  ASSERT_TRUE(doc.isOk());
  const LodProfile profile{.baseLevel = 2, .maxLevel = 5, .angleThresholdDegrees = 10};
  auto t = Tessellation::build(*doc, profile);
  ASSERT_TRUE(t.isOk()) << t.status().message();
  std::mt19937 rng(5);
  auto pick = [&](uint64_t n) { return std::uniform_int_distribution<uint64_t>(0, n - 1)(rng); };
  std::vector<EditId> made, undone;
  for (int step = 0; step < 80; ++step) {
    std::vector<VertexId> limits;
    const int batch = 1 + static_cast<int>(pick(6));
    for (int e = 0; e < batch; ++e) {
      const int op = static_cast<int>(pick(20));
      if (op < 14) {
        const VertexId v(2, pick(98));
        const Vec3 d(0.01 * (static_cast<double>(pick(21)) - 10) / 10,
                     0.01 * (static_cast<double>(pick(21)) - 10) / 10, 0.005);
        auto id = doc->moveBy(std::span(&v, 1), d);
        ASSERT_TRUE(id.isOk());
        made.push_back(*id);
      } else if (op < 16 && !made.empty()) {
        const EditId id = made.back();
        made.pop_back();
        ASSERT_TRUE(doc->undo(id).isOk());
        undone.push_back(id);
      } else if (op < 18 && !undone.empty()) {
        const EditId id = undone.back();
        undone.pop_back();
        ASSERT_TRUE(doc->redo(id).isOk());
        made.push_back(id);
      } else if (op == 18) {
        const int level = 1 + static_cast<int>(pick(2));
        if (!doc->setEdgeSharpness(EdgeId(level, pick(doc->counts().edges(level))),
                                   pick(2) ? 2.0f : kSharpnessInfinite)
                 .isOk())
          continue;
      } else {
        if (!doc->setVertexSharpness(VertexId(1, pick(doc->counts().vertices(1))), kSharpnessInfinite).isOk())
          continue;
      }
      limits.insert(limits.end(), doc->lastUpdate().limits.begin(), doc->lastUpdate().limits.end());
    }
    std::sort(limits.begin(), limits.end());
    limits.erase(std::unique(limits.begin(), limits.end()), limits.end());
    auto changes = t->update(*doc, limits);
    ASSERT_TRUE(changes.isOk()) << changes.status().message();
    auto fresh = Tessellation::build(*doc, profile);
    ASSERT_TRUE(fresh.isOk());
    expectSameRegions(*t, *fresh, "step " + std::to_string(step));
    if (::testing::Test::HasFatalFailure()) return;
  }
}

TEST(Tessellation, RefusesProfilesOverTheirTriangleBudget) {
  const TestMesh mesh = testing::icosahedron();
  auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = 4});
  ASSERT_TRUE(doc.isOk());
  // Over budget by its base level alone (4 of 20 triangles: 5120): refused
  // from the level counts, before the hierarchy grows to that level.
  const int levelsBefore = doc->hierarchy().numLevels();
  auto t = Tessellation::build(*doc, {.baseLevel = 4, .maxLevel = 4, .triangleBudget = 1000});
  ASSERT_FALSE(t.isOk());
  EXPECT_NE(
      t.status().message().find("needs at least 5120 triangles (its base level 4), above its budget of 1000"),
      std::string::npos)
      << t.status().message();
  EXPECT_EQ(doc->hierarchy().numLevels(), levelsBefore);
  // Within budget at its base level, over it once refined everywhere (a tiny
  // angle threshold): refused after the cut.
  auto refined = Tessellation::build(
      *doc, {.baseLevel = 1, .maxLevel = 4, .angleThresholdDegrees = 1e-3, .triangleBudget = 1000});
  ASSERT_FALSE(refined.isOk());
  EXPECT_NE(refined.status().message().find("5120 triangles, above its budget of 1000"), std::string::npos)
      << refined.status().message();
  auto bad = Tessellation::build(*doc, {.baseLevel = 3, .maxLevel = 2});
  ASSERT_FALSE(bad.isOk());
  EXPECT_NE(bad.status().message().find("max level 2 is below the base level 3"), std::string::npos);
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// §3.1.2 and Color Plate 1(h): on a flat sheet every limit normal agrees,
// so only the crease-tangent test can refine along a curved crease -- and
// it must, while the sheet without the crease stays at its base triangles.
TEST(Tessellation, RefinesAlongCurvedCreasesWhereNormalsAgree) {
  TestMesh sheet = testing::openGrid(6, 6);
  for (Vec3& p : sheet.points) p[2] = 0.0;
  auto id = [](int i, int j) { return i * 7 + j; };
  // Sharp square corners keep the sheet's boundary straight.
  sheet.topology.vertexSharpness.assign(sheet.topology.numVertices, 0.0f);
  for (int v : {id(0, 0), id(0, 6), id(6, 0), id(6, 6)})
    sheet.topology.vertexSharpness[v] = kSharpnessInfinite;
  const int stairs[][2] = {{1, 1}, {2, 1}, {2, 2}, {3, 2}, {3, 3}, {4, 3}, {4, 4}, {5, 4}};
  TestMesh creased = sheet;
  for (int k = 0; k + 1 < 8; ++k) {
    creased.topology.creases.push_back(
        {id(stairs[k][0], stairs[k][1]), id(stairs[k + 1][0], stairs[k + 1][1]), kSharpnessInfinite});
  }
  const LodProfile profile{.baseLevel = 0, .maxLevel = 4, .angleThresholdDegrees = 10};
  int64_t triangles[2];
  for (int k = 0; k < 2; ++k) {
    const TestMesh& mesh = k == 0 ? sheet : creased;
    auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = 4});
    ASSERT_TRUE(doc.isOk()) << doc.status().message();
    auto t = Tessellation::build(*doc, profile);
    ASSERT_TRUE(t.isOk());
    triangles[k] = t->numTriangles();
    expectSoundTessellation(*doc, *t, mesh.name);
  }
  EXPECT_EQ(triangles[0], 72);
  EXPECT_GT(triangles[1], 2 * triangles[0]);
}

// §3.1.1: fidelity shows the faces around an edited vertex one level finer.
TEST(Tessellation, FidelityRefinesAroundEditsOneLevelFurther) {
  const TestMesh mesh = testing::torus(12, 8);
  auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = 4});
  ASSERT_TRUE(doc.isOk());
  const VertexId v(2, 5);
  ASSERT_TRUE(doc->moveBy(std::span(&v, 1), Vec3(0, 0, 0.05)).isOk());
  LodProfile profile{.baseLevel = 1, .maxLevel = 4, .angleThresholdDegrees = 60};
  auto plain = Tessellation::build(*doc, profile);
  profile.fidelity = true;
  auto fine = Tessellation::build(*doc, profile);
  ASSERT_TRUE(plain.isOk() && fine.isOk());
  EXPECT_GT(fine->numTriangles(), plain->numTriangles());
  expectSoundTessellation(*doc, *fine, "fidelity");
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// The copies of crease and corner vertices (one per side, each with its
// sector's normal) stitch into an oriented closed 2-manifold: every
// directed edge between vertex ids is used once and its reverse once, the
// triangles around each vertex id form one fan, and so do the triangles
// that use one copy (id and normal, as mergeRegions joins them) of a
// vertex with several, joined across edges to the same copy of the
// neighbour -- what a mesh reader checks of the merged export.
void expectManifoldCopies(const Tessellation& t, const std::string& where) {
  using Copy = std::pair<uint64_t, std::array<double, 3>>;
  struct Corner {
    Copy prev, next;  // the vertices before and after this one in the triangle
  };
  auto name = [](const Copy& c) {
    return VertexId::fromPacked(c.first).toString() + " (normal " + std::to_string(c.second[0]) + " " +
           std::to_string(c.second[1]) + " " + std::to_string(c.second[2]) + ")";
  };
  std::map<std::pair<uint64_t, uint64_t>, int> directed;
  std::map<Copy, std::vector<Corner>> copies;
  std::map<uint64_t, std::vector<Corner>> around;  // with the neighbours' ids only
  for (const auto& [region, mesh] : t.regions()) {
    auto copyOf = [&](int i) {
      const Vec3& n = mesh.normals[i];
      return Copy{mesh.vertexIds[i], {n[0], n[1], n[2]}};
    };
    for (const auto& tri : mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        const Copy v = copyOf(tri[k]), next = copyOf(tri[(k + 1) % 3]), prev = copyOf(tri[(k + 2) % 3]);
        ++directed[{v.first, next.first}];
        copies[v].push_back({prev, next});
        around[v.first].push_back({{prev.first, {}}, {next.first, {}}});
      }
    }
  }
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << where << ": directed edge " << VertexId::fromPacked(edge.first).toString() << "-"
                        << VertexId::fromPacked(edge.second).toString() << " used " << count << " times";
    ASSERT_EQ(directed.count({edge.second, edge.first}), 1u)
        << where << ": edge " << VertexId::fromPacked(edge.first).toString() << "-"
        << VertexId::fromPacked(edge.second).toString() << " has no reverse";
  }
  // The connected pieces of a set of corners around one vertex: corners
  // join where one's next is another's prev (the same edge, to the same
  // neighbour). Returns the first corner of a second piece, or -1.
  auto secondPiece = [](const std::vector<Corner>& corners) {
    std::vector<int> parent(corners.size());
    for (size_t i = 0; i < corners.size(); ++i) parent[i] = static_cast<int>(i);
    auto find = [&](int i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    std::map<Copy, int> byPrev;
    for (size_t i = 0; i < corners.size(); ++i) byPrev[corners[i].prev] = static_cast<int>(i);
    for (size_t i = 0; i < corners.size(); ++i) {
      auto it = byPrev.find(corners[i].next);
      if (it != byPrev.end()) parent[find(static_cast<int>(i))] = find(it->second);
    }
    for (size_t i = 1; i < corners.size(); ++i) {
      if (find(static_cast<int>(i)) != find(0)) return static_cast<int>(i);
    }
    return -1;
  };
  for (const auto& [v, corners] : around) {
    ASSERT_EQ(secondPiece(corners), -1) << where << ": the triangles around "
                                        << VertexId::fromPacked(v).toString() << " form more than one fan";
  }
  std::map<uint64_t, int> copiesOf;
  for (const auto& [copy, corners] : copies) ++copiesOf[copy.first];
  for (const auto& [copy, corners] : copies) {
    // Sides whose normals are equal (a crease across a flat area) are one
    // copy in the merged surface, which may then pinch there; what matters
    // here is that distinct sides are used consistently.
    if (copiesOf[copy.first] == 1) continue;
    const int second = secondPiece(corners);
    ASSERT_EQ(second, -1) << where << ": the triangles using one copy of " << name(copy)
                          << " form more than one fan, e.g. the one from " << name(corners[0].next) << " to "
                          << name(corners[0].prev) << " and the one from " << name(corners[second].next)
                          << " to " << name(corners[second].prev);
  }
}

// The creased cube's corner (1,1,1) -- a tagged corner between two
// infinitely sharp rim edges and a 2.5-sharp vertical edge -- after a
// level-4 move nearby: its limit is taken at a level where the vertical
// edge has decayed (3 sectors shown, 2 at the limit's level), and each
// triangle must still use the copy of the sector it lies in (the CLI's
// adaptive export once was non-manifold there).
TEST(Tessellation, CreaseCopiesFormOneFanPerSideAtADecayedCorner) {
  auto mesh = testing::creasedCube();
  ASSERT_TRUE(mesh.isOk()) << mesh.status().message();
  auto doc = Document::create(*mesh, {.maxLevel = 6});
  ASSERT_TRUE(doc.isOk());
  const VertexId v(4, 3);
  ASSERT_TRUE(doc->moveBy(std::span(&v, 1), Vec3(0, 0, 0.05)).isOk());
  const LodProfile profile{.baseLevel = 1, .maxLevel = 4, .angleThresholdDegrees = 20};
  auto t = Tessellation::build(*doc, profile);
  ASSERT_TRUE(t.isOk()) << t.status().message();
  expectManifoldCopies(*t, "cube, v4:3 moved");
}

// The same over random edits (moves and creases) of the creased cube and a
// tagged torus, fresh and updated edit by edit.
TEST(Tessellation, CreaseCopiesFormOneFanPerSideAfterRandomEdits) {
  auto cube = testing::creasedCube();
  ASSERT_TRUE(cube.isOk()) << cube.status().message();
  const TestMesh torus = testing::withRandomTags(testing::torus(8, 6), 0.15, 0.05, 3);
  const std::vector<LodProfile> profiles = {
      {.baseLevel = 1, .maxLevel = 4, .angleThresholdDegrees = 20},
      {.baseLevel = 2, .maxLevel = 5, .angleThresholdDegrees = 10},
  };
  for (int which = 0; which < 2; ++which) {
    for (uint32_t seed : {31u, 32u, 33u}) {
      auto doc = which == 0 ? Document::create(*cube, {.maxLevel = 6})
                            : Document::create(torus.topology, torus.points, {.maxLevel = 5});
      ASSERT_TRUE(doc.isOk());
      const std::string name = (which == 0 ? "cube" : torus.name) + " seed " + std::to_string(seed);
      std::vector<Tessellation> kept;
      for (const LodProfile& profile : profiles) {
        auto t = Tessellation::build(*doc, profile);
        ASSERT_TRUE(t.isOk()) << t.status().message();
        kept.push_back(std::move(*t));
      }
      for (int step = 0; step < 8; ++step) {
        // One edit at a time, so that lastUpdate() covers it (a refused
        // crease leaves the previous one there: updating it again is fine).
        randomEdits(*doc, 1, seed * 100 + step,
                    seed % 3 == 0 ? kSharpnessInfinite : (which == 0 ? 2.0f : 1.5f));
        for (size_t p = 0; p < profiles.size(); ++p) {
          const std::string where = name + " step " + std::to_string(step) + " profile " + profiles[p].key();
          auto changes = kept[p].update(*doc);
          ASSERT_TRUE(changes.isOk()) << changes.status().message();
          expectManifoldCopies(kept[p], where + " (updated)");
          auto fresh = Tessellation::build(*doc, profiles[p]);
          ASSERT_TRUE(fresh.isOk()) << fresh.status().message();
          expectManifoldCopies(*fresh, where + " (fresh)");
          testing::expectSameRegions(kept[p], *fresh, where);
          if (HasFatalFailure()) return;
        }
      }
    }
  }
}

}  // namespace
}  // namespace tessera
