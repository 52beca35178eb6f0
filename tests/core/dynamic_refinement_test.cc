// Dynamic refinement (core/render/dynamic_refinement.h): edge decisions and points are
// bit-identical from either end and either side; regions of a real
// tessellation refined separately fit together watertight; and a refined
// coarse LOD is closer to the limit surface than the coarse LOD itself.
#include <gtest/gtest.h>

#include <bit>
#include <cstdio>
#include <map>
#include <random>

#include "core/document/document.h"
#include "core/render/dynamic_refinement.h"
#include "core/render/surface_distance.h"
#include "core/tessellation/document_grid.h"
#include "core/tessellation/tessellation.h"
#include "support/procedural_meshes.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using testing::TestMesh;

bool same(const Vec3& a, const Vec3& b) {
  return bitsEqual(a, b);
}

Vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

TEST(EdgeSplit, DecisionAndPointsAreTheSameFromEitherEndAndSide) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), bend(0.0, 0.3);
  int bySplits[3] = {0, 0, 0};
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 p0(u(rng), u(rng), u(rng)), p1(u(rng), u(rng), u(rng));
    const Vec3 n = randomUnit(rng);
    const double b = bend(rng);
    const EdgeSide a{(n + b * randomUnit(rng)).normalized(), (n + b * randomUnit(rng)).normalized()};
    std::optional<EdgeSide> other;
    if (trial % 2) other = EdgeSide{randomUnit(rng), randomUnit(rng)};  // a crease: the far side differs
    const EdgeSplit s = splitEdge(p0, p1, a, other, {});
    const EdgeSplit reversed =
        splitEdge(p1, p0, {a.n1, a.n0},
                  other ? std::optional<EdgeSide>(EdgeSide{other->n1, other->n0}) : std::nullopt, {});
    ++bySplits[s.splits];
    ASSERT_EQ(s.splits, reversed.splits) << "trial " << trial;
    for (int q = 0; q < 3; ++q) {
      ASSERT_TRUE(same(s.points[q], reversed.points[2 - q])) << "trial " << trial << " point " << q;
      ASSERT_TRUE(same(s.normals[q], reversed.normals[2 - q])) << "trial " << trial << " normal " << q;
      ASSERT_TRUE(same(s.otherNormals[q], reversed.otherNormals[2 - q])) << "trial " << trial;
    }
    if (!other) continue;
    const EdgeSplit across = splitEdge(p1, p0, {other->n1, other->n0}, EdgeSide{a.n1, a.n0}, {});
    ASSERT_EQ(s.splits, across.splits) << "trial " << trial;
    for (int q = 0; q < 3; ++q) {
      ASSERT_TRUE(same(s.points[q], across.points[2 - q]))
          << "trial " << trial << " point " << q << " across";
      ASSERT_TRUE(same(s.normals[q], across.otherNormals[2 - q])) << "trial " << trial << " across";
    }
  }
  // The random bends reach every decision, so the checks above saw all three.
  EXPECT_GT(bySplits[0], 50);
  EXPECT_GT(bySplits[1], 50);
  EXPECT_GT(bySplits[2], 50);
}

Document cubeDocument() {
  auto mesh = testing::creasedCube();
  EXPECT_TRUE(mesh.isOk()) << mesh.status().message();
  auto doc = Document::create(*mesh, {.maxLevel = 5});
  EXPECT_TRUE(doc.isOk()) << doc.status().message();
  return std::move(*doc);
}

RefineInput inputOf(const RegionMesh& m) {
  return {m.positions, m.normals, m.triangles};
}

// Every region refined on its own, told the border normals of all (or not).
std::vector<RefinedMesh> refineRegions(const Tessellation& t, const SplitCriterion& c, bool withBorders) {
  std::vector<RefineInput> inputs;
  for (const auto& [id, m] : t.regions()) inputs.push_back(inputOf(m));
  if (withBorders) {
    auto all = refineMeshes(inputs, c);
    EXPECT_TRUE(all.isOk()) << all.status().message();
    return all.isOk() ? std::move(*all) : std::vector<RefinedMesh>{};
  }
  std::vector<RefinedMesh> out;
  for (const RefineInput& in : inputs) {
    auto r = refineMesh(in, c);
    EXPECT_TRUE(r.isOk()) << r.status().message();
    out.push_back(std::move(*r));
  }
  return out;
}

struct Merged {
  std::vector<Vec3> positions;
  std::vector<std::array<int, 3>> triangles;
  MeshView view() const { return {positions, triangles}; }
};

// Vertices merged by their position bits only: what a viewer sees on screen.
template <typename Mesh>
Merged mergeByPosition(const std::vector<const Mesh*>& meshes) {
  Merged out;
  std::map<std::array<uint64_t, 3>, int> index;
  for (const Mesh* m : meshes) {
    for (const auto& t : m->triangles) {
      std::array<int, 3> tri{};
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = m->positions[t[k]];
        const std::array<uint64_t, 3> key{std::bit_cast<uint64_t>(p[0]), std::bit_cast<uint64_t>(p[1]),
                                          std::bit_cast<uint64_t>(p[2])};
        auto [it, fresh] = index.try_emplace(key, static_cast<int>(out.positions.size()));
        if (fresh) out.positions.push_back(p);
        tri[k] = it->second;
      }
      out.triangles.push_back(tri);
    }
  }
  return out;
}

// Closed and oriented: every directed edge once and its reverse once.
int unmatchedEdges(const Merged& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  int bad = 0;
  for (const auto& [e, n] : directed) {
    const auto twin = directed.find({e.second, e.first});
    bad += (n != 1 || twin == directed.end() || twin->second != 1) ? 1 : 0;
  }
  return bad;
}

template <typename Mesh>
std::vector<const Mesh*> pointers(const std::vector<Mesh>& v) {
  std::vector<const Mesh*> out;
  for (const Mesh& m : v) out.push_back(&m);
  return out;
}

std::vector<const RegionMesh*> pointers(const Tessellation& t) {
  std::vector<const RegionMesh*> out;
  for (const auto& [id, m] : t.regions()) out.push_back(&m);
  return out;
}

TEST(DynamicRefinement, RegionsRefinedSeparatelyAreWatertight) {
  Document cube = cubeDocument();
  const TestMesh torus = testing::withRandomTags(testing::torus(8, 6), 0.15, 0.05, 3);
  auto torusDoc = Document::create(torus.topology, torus.points, {.maxLevel = 4});
  ASSERT_TRUE(torusDoc.isOk());
  struct Case {
    const char* name;
    Document* doc;
    LodProfile profile;
  } cases[] = {
      // Deepest level 4: a region per base face (a coarser profile groups
      // these small meshes' faces into one or two regions).
      {"cube", &cube, {.baseLevel = 1, .maxLevel = 4, .angleThresholdDegrees = 15}},
      {"torus with random tags", &*torusDoc, {.baseLevel = 0, .maxLevel = 4, .angleThresholdDegrees = 20}}};
  for (auto& c : cases) {
    auto t = Tessellation::build(*c.doc, c.profile);
    ASSERT_TRUE(t.isOk()) << c.name << ": " << t.status().message();
    ASSERT_GT(t->regions().size(), 4u) << c.name;
    ASSERT_EQ(unmatchedEdges(mergeByPosition(pointers(*t))), 0) << c.name << ": the input is closed";
    for (int maxSplits : {1, 2}) {
      const auto refined = refineRegions(*t, {.maxSplits = maxSplits}, true);
      const Merged merged = mergeByPosition(pointers(refined));
      EXPECT_EQ(unmatchedEdges(merged), 0) << c.name << ", " << maxSplits << " splits";
      EXPECT_GT(merged.triangles.size(), 3 * t->numTriangles() / 2) << c.name << ": refinement did little";
      for (const auto& tri : merged.triangles) {
        const Vec3 n = (merged.positions[tri[1]] - merged.positions[tri[0]]) %
                       (merged.positions[tri[2]] - merged.positions[tri[0]]);
        ASSERT_GT(n.norm(), 1e-12) << c.name << ": a refined triangle has no area";
      }
    }
  }
  // The cube's creases lie on region borders: without the neighbours'
  // normals the two sides of a crease place their points apart.
  auto t = Tessellation::build(cube, cases[0].profile);
  ASSERT_TRUE(t.isOk());
  EXPECT_GT(unmatchedEdges(mergeByPosition(pointers(refineRegions(*t, {.maxSplits = 2}, false)))), 0);
  // As a client holds them: every region encoded on the document's grid
  // and decoded on its own. Border vertices decode bit-identically, normals
  // included, so the refined regions still fit.
  auto grid = documentGrid(cube);
  ASSERT_TRUE(grid.isOk());
  std::vector<RegionMesh> decoded;
  for (const auto& [id, m] : t->regions()) {
    auto bytes =
        encodeRegion({.regionId = id, .documentVersion = 1, .profile = t->profile(), .grid = *grid}, m);
    ASSERT_TRUE(bytes.isOk()) << bytes.status().message();
    auto back = decodeRegion(*bytes);
    ASSERT_TRUE(back.isOk()) << back.status().message();
    decoded.push_back(std::move(back->second));
  }
  std::vector<RefineInput> inputs;
  for (const RegionMesh& m : decoded) inputs.push_back(inputOf(m));
  auto fromDecoded = refineMeshes(inputs, {.maxSplits = 2});
  ASSERT_TRUE(fromDecoded.isOk());
  EXPECT_EQ(unmatchedEdges(mergeByPosition(pointers(decoded))), 0);
  EXPECT_EQ(unmatchedEdges(mergeByPosition(pointers(*fromDecoded))), 0)
      << "decoded regions crack when refined";

  // By hand, as a client that refines only some regions would: the same.
  BorderEdges borders;
  for (const auto& [id, m] : t->regions()) ASSERT_TRUE(addBorderEdges(inputOf(m), borders).isOk());
  const auto all = refineRegions(*t, {.maxSplits = 2}, true);
  size_t i = 0;
  for (const auto& [id, m] : t->regions()) {
    auto one = refineMesh(inputOf(m), {.maxSplits = 2}, &borders);
    ASSERT_TRUE(one.isOk());
    EXPECT_EQ(one->positions, all[i].positions);
    EXPECT_EQ(one->triangles, all[i++].triangles);
  }
}

struct Distances {
  SurfaceDistance coarse, once, twice;
};

Distances distancesToDense(Document& doc, const LodProfile& coarse, int denseLevel) {
  auto dense = Tessellation::build(
      doc, {.baseLevel = denseLevel, .maxLevel = denseLevel, .angleThresholdDegrees = 90});
  auto t = Tessellation::build(doc, coarse);
  EXPECT_TRUE(dense.isOk() && t.isOk());
  const Merged reference = mergeByPosition(pointers(*dense));
  Distances d;
  d.coarse = surfaceDistance(mergeByPosition(pointers(*t)).view(), reference.view());
  d.once = surfaceDistance(mergeByPosition(pointers(refineRegions(*t, {.maxSplits = 1}, true))).view(),
                           reference.view());
  d.twice = surfaceDistance(mergeByPosition(pointers(refineRegions(*t, {.maxSplits = 2}, true))).view(),
                            reference.view());
  std::printf("rms %.5f %.5f %.5f  max %.5f %.5f %.5f  (coarse, 1 split, 2 splits)\n", d.coarse.rms,
              d.once.rms, d.twice.rms, d.coarse.max, d.once.max, d.twice.max);
  return d;
}

TEST(DynamicRefinement, RefinedCoarseLodIsCloserToTheDenseLimitSurface) {
  Document cube = cubeDocument();
  const TestMesh ico = testing::icosahedron();
  auto smooth = Document::create(ico.topology, ico.points, {.maxLevel = 5});
  ASSERT_TRUE(smooth.isOk());
  for (Document* doc : {&cube, &*smooth}) {
    const Distances d =
        distancesToDense(*doc, {.baseLevel = 1, .maxLevel = 2, .angleThresholdDegrees = 20}, 5);
    EXPECT_LT(d.once.rms, 0.8 * d.coarse.rms);
    EXPECT_LT(d.twice.rms, d.once.rms);
    EXPECT_LT(d.once.max, d.coarse.max);
    EXPECT_LE(d.twice.max, d.once.max * 1.05);
  }
}

TEST(DynamicRefinement, RejectsBadInput) {
  const std::vector<Vec3> p{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, n(3, Vec3(0, 0, 1));
  const std::vector<std::array<int, 3>> good{{0, 1, 2}}, bad{{0, 1, 3}}, repeated{{0, 1, 1}};
  EXPECT_TRUE(refineMesh({p, n, good}, {}).isOk());
  EXPECT_FALSE(refineMesh({p, n, bad}, {}).isOk());
  EXPECT_FALSE(refineMesh({p, n, repeated}, {}).isOk());
  EXPECT_FALSE(refineMesh({p, std::span<const Vec3>(n).first(2), good}, {}).isOk());
  EXPECT_FALSE(refineMesh({p, n, good}, {.maxSplits = 3}).isOk());
  EXPECT_FALSE(refineMesh({p, n, good}, {.splitOnceBelow = 0.5, .splitTwiceBelow = 0.9}).isOk());
}

}  // namespace
}  // namespace tessera
