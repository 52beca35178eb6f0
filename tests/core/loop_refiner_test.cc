// Structural properties of uniform Loop refinement (the oracle suite checks
// the values against OpenSubdiv; these check counts, topology and errors).
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "core/loop/loop_refiner.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

TEST(LoopRefiner, CountsFollowOneToFourSplit) {
  auto mesh = testing::torus(6, 5);
  auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = 3});
  ASSERT_TRUE(refiner.isOk()) << refiner.status().toString();
  for (int l = 0; l < 3; ++l) {
    const Level& p = refiner->level(l);
    const Level& c = refiner->level(l + 1);
    EXPECT_EQ(c.numFaces(), 4 * p.numFaces());
    EXPECT_EQ(c.numEdges(), 2 * p.numEdges() + 3 * p.numFaces());
    EXPECT_EQ(c.numVertices, p.numVertices + p.numEdges());
    // Euler characteristic of a torus stays 0 at every level.
    EXPECT_EQ(c.numVertices - c.numEdges() + c.numFaces(), 0);
  }
}

TEST(LoopRefiner, ClosedMeshStaysWatertightAndOriented) {
  auto mesh = testing::withRandomFlips(testing::icosahedron(), 5, 3);
  auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = 3});
  ASSERT_TRUE(refiner.isOk());
  const Level& fine = refiner->finestLevel();
  // Every directed edge appears once, and its reverse once: closed, manifold, oriented.
  std::map<std::pair<int, int>, int> directed;
  for (Index t = 0; t < fine.numFaces(); ++t) {
    const auto f = fine.triangleVertices(t);
    for (int j = 0; j < 3; ++j) ++directed[{f[j], f[(j + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
  EXPECT_EQ(directed.size(), 2u * fine.numEdges());
}

TEST(LoopRefiner, FirstVerticesAreImagesOfInputVertices) {
  // A corner vertex keeps its position exactly: vertex i of every level is
  // the image of input vertex i.
  auto mesh = testing::icosahedron();
  mesh.topology.vertexSharpness.assign(12, 0.0f);
  for (int v : {2, 7, 11}) mesh.topology.vertexSharpness[v] = kSharpnessInfinite;
  auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = 3});
  ASSERT_TRUE(refiner.isOk());
  auto fine = refiner->refinePoints(mesh.points);
  for (int v : {2, 7, 11}) EXPECT_EQ(fine[v], mesh.points[v]);
}

TEST(LoopRefiner, FacesOnlyLastLevelGivesIdenticalPoints) {
  auto mesh = testing::withRandomTags(testing::torus(8, 6), 0.3, 0.05, 9);
  for (CreaseMethod method : {CreaseMethod::kUniform, CreaseMethod::kChaikin}) {
    LoopOptions options;
    options.creaseMethod = method;
    auto full = LoopRefiner::create(mesh.topology, options, {.levels = 3});
    auto lean = LoopRefiner::create(mesh.topology, options, {.levels = 3, .fullTopologyInLastLevel = false});
    ASSERT_TRUE(full.isOk() && lean.isOk());
    EXPECT_EQ(full->refinePoints(mesh.points), lean->refinePoints(mesh.points));
    EXPECT_EQ(full->finestLevel().faceVertices, lean->finestLevel().faceVertices);
    EXPECT_FALSE(lean->limitSurface(lean->refinePoints(mesh.points)).isOk());
  }
}

TEST(LoopRefiner, RejectsBadTopologyWithClearErrors) {
  BaseTopology t;
  t.numVertices = 4;
  t.triangles = {{0, 1, 2}, {0, 1, 3}};  // both run 0->1: inconsistent orientation
  auto r = LoopRefiner::create(t, {}, {.levels = 1});
  ASSERT_FALSE(r.isOk());
  EXPECT_NE(r.status().message().find("inconsistently oriented"), std::string::npos) << r.status().message();

  // A closed tetrahedron plus a fin on edge 0-1: three faces on one edge.
  t.triangles = {{0, 1, 2}, {1, 0, 3}, {2, 1, 3}, {0, 2, 3}, {1, 0, 2}};
  r = LoopRefiner::create(t, {}, {.levels = 1});
  ASSERT_FALSE(r.isOk());
  EXPECT_NE(r.status().message().find("non-manifold"), std::string::npos) << r.status().message();

  t.triangles = {{0, 1, 2}};
  r = LoopRefiner::create(t, {}, {.levels = 1});
  ASSERT_FALSE(r.isOk());
  EXPECT_NE(r.status().message().find("vertex 3 is not used"), std::string::npos) << r.status().message();

  t.triangles = {{0, 1, 2}, {0, 2, 3}};
  t.creases = {{1, 3, 1.0f}};
  r = LoopRefiner::create(t, {}, {.levels = 1});
  ASSERT_FALSE(r.isOk());
  EXPECT_NE(r.status().message().find("share no edge"), std::string::npos) << r.status().message();
}

TEST(LoopRefiner, RefusesLevelsBeyondTheFaceBudget) {
  auto mesh = testing::icosahedron();
  auto r = LoopRefiner::create(mesh.topology, {}, {.levels = 6, .maxFaces = 20 * 1024});
  ASSERT_FALSE(r.isOk());
  EXPECT_NE(r.status().message().find("would exceed"), std::string::npos);
  EXPECT_FALSE(LoopRefiner::create(mesh.topology, {}, {.levels = -1}).isOk());
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

TEST(LoopRefiner, SurfacesCarryOutwardUnitNormals) {
  // On a sphere-like closed mesh centred at the origin, every normal of the
  // control and limit surfaces points away from the centre.
  auto mesh = testing::icosahedron();
  auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = 2});
  ASSERT_TRUE(refiner.isOk());
  auto points = refiner->refinePoints(mesh.points);
  auto limit = refiner->limitSurface(points);
  ASSERT_TRUE(limit.isOk());
  for (const SurfaceMesh& s : {refiner->controlSurface(points), limit.value()}) {
    ASSERT_EQ(s.normals.size(), s.positions.size());
    ASSERT_EQ(s.triangles.size(), 320u);
    for (size_t v = 0; v < s.positions.size(); ++v) {
      EXPECT_NEAR(s.normals[v].norm(), 1.0, 1e-12);
      EXPECT_GT(dot(s.normals[v], s.positions[v].normalized()), 0.95) << "vertex " << v;
    }
  }
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// A cube whose twelve edges are all infinitely sharp refines to the cube
// itself: flat faces, sharp edges, corners. Each face corner of the limit
// surface must therefore carry the normal of its cube face exactly, which
// needs vertices split along the creases (one normal per side).
TEST(LoopRefiner, LimitSurfaceSplitsCreasesIntoOneNormalPerSide) {
  BaseTopology cube;
  cube.numVertices = 8;
  cube.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                    {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  const int cubeEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (const auto& e : cubeEdges) cube.creases.push_back({e[0], e[1], kSharpnessInfinite});
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int levels : {1, 3}) {
    auto refiner = LoopRefiner::create(cube, {}, {.levels = levels});
    ASSERT_TRUE(refiner.isOk());
    auto limit = refiner->limitSurface(refiner->refinePoints(points));
    ASSERT_TRUE(limit.isOk());
    const SurfaceMesh& s = *limit;
    const int levelVertices = refiner->finestLevel().numVertices;
    EXPECT_GT(static_cast<int>(s.positions.size()), levelVertices);  // creases were split
    for (size_t t = 0; t < s.triangles.size(); ++t) {
      const auto& tri = s.triangles[t];
      const Vec3 faceNormal =
          ((s.positions[tri[1]] - s.positions[tri[0]]) % (s.positions[tri[2]] - s.positions[tri[0]]))
              .normalized();
      for (int c : tri) {
        EXPECT_NEAR(dot(s.normals[c], faceNormal), 1.0, 1e-9) << "triangle " << t << " corner vertex " << c;
      }
    }
    // Copies sit exactly on their originals.
    for (int v = levelVertices; v < static_cast<int>(s.positions.size()); ++v) {
      bool onOriginal = false;
      for (int u = 0; u < levelVertices && !onOriginal; ++u) onOriginal = s.positions[u] == s.positions[v];
      EXPECT_TRUE(onOriginal) << v;
    }
  }
}

}  // namespace
}  // namespace tessera
