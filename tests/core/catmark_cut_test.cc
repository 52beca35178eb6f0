// The adaptive cut and its crack-free leaves on Catmull-Clark documents
// (core/tessellation/adaptive_cut.h, leaf_triangulation.h): on closed
// polygon meshes, after random edits and after every incremental
// re-decision, the leaves' triangles form a closed, consistently oriented
// surface -- every directed edge once, its reverse once -- with no
// degenerate triangle, and every vertex a corner of a triangle where it lies
// on another leaf's edge (no T-vertex, which a closed edge count implies).
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>

#include "core/document/document.h"
#include "core/tessellation/adaptive_cut.h"
#include "core/tessellation/leaf_triangulation.h"
#include "support/polygon_meshes.h"

namespace tessera {
namespace {

using testing::PolyTestMesh;

struct Shown {
  long long triangles = 0, leaves = 0, quadLeavesWithPoints = 0;
  std::set<int> leafLevels;
};

// The point a vertex of the hierarchy is: its index at its birth level (a
// vertex's child keeps its index, hierarchy/ids.h).
std::pair<int, uint64_t> pointOf(const Document& doc, VertexRef ref) {
  const uint64_t index = doc.hierarchy().level(ref.level).vertexIds[ref.local];
  return {doc.counts().birthLevel(VertexId(ref.level, index)), index};
}

void expectClosedAndOriented(const Document& doc, const AdaptiveCut& cut, const std::string& when,
                             Shown& shown) {
  const SparseHierarchy& h = doc.hierarchy();
  std::map<std::pair<std::pair<int, uint64_t>, std::pair<int, uint64_t>>, int> directed;
  for (int l = 0; l < cut.numLevels(); ++l) {
    for (Index f = 0; f < h.level(l).mesh.numFaces(); ++f) {
      if (!cut.isNode(h, l, f) || cut.isSplit(l, f)) continue;
      std::vector<RefTriangle> triangles;
      triangulateLeaf(h, cut, l, f, triangles);
      ++shown.leaves;
      shown.leafLevels.insert(l);
      if (l > 0 && triangles.size() > 2) ++shown.quadLeavesWithPoints;
      for (const RefTriangle& t : triangles) {
        const std::array<std::pair<int, uint64_t>, 3> p = {pointOf(doc, t[0]), pointOf(doc, t[1]),
                                                           pointOf(doc, t[2])};
        ASSERT_TRUE(p[0] != p[1] && p[1] != p[2] && p[2] != p[0]) << when << ": a degenerate triangle";
        for (int k = 0; k < 3; ++k) ++directed[{p[k], p[(k + 1) % 3]}];
        ++shown.triangles;
      }
    }
  }
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << when << ": directed edge v" << edge.first.first << ":" << edge.first.second
                        << " -> v" << edge.second.first << ":" << edge.second.second << " used " << count
                        << " times";
    const auto reverse = directed.find({edge.second, edge.first});
    ASSERT_TRUE(reverse != directed.end())
        << when << ": a crack at v" << edge.first.first << ":" << edge.first.second << " -> v"
        << edge.second.first << ":" << edge.second.second;
  }
}

void checkCut(const PolyTestMesh& mesh, uint32_t seed, Shown& shown) {
  SCOPED_TRACE(mesh.name);
  auto doc =
      Document::create(mesh.topology, mesh.points, {.maxLevel = 5, .scheme = DocumentScheme::kCatmullClark});
  ASSERT_TRUE(doc.isOk()) << doc.status().toString();
  const LodProfile profile{.baseLevel = 0, .maxLevel = 4, .angleThresholdDegrees = 12};
  auto cut = AdaptiveCut::build(*doc, profile);
  ASSERT_TRUE(cut.isOk()) << cut.status().toString();
  expectClosedAndOriented(*doc, *cut, "without edits", shown);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int step = 0; step < 30; ++step) {
    const int l = step % 5;
    const VertexId v(
        l, static_cast<uint64_t>((unit(rng) + 1) / 2 * static_cast<double>(doc->counts().vertices(l))));
    Expected<EditId> id = step % 7 == 3
                              ? doc->setEdgeSharpness(EdgeId(l, v.index() % doc->counts().edges(l)), 2.5f)
                              : doc->moveBy(std::span(&v, 1), Vec3(unit(rng), unit(rng), unit(rng)) * 0.15);
    if (!id.isOk()) continue;
    // The re-decision around the changed limits, or a new cut after growth.
    auto flipped =
        cut->isCurrent(doc->hierarchy()) ? cut->redecide(*doc, doc->lastUpdate().limits) : std::nullopt;
    if (!flipped || !cut->isCurrent(doc->hierarchy())) {
      auto rebuilt = AdaptiveCut::build(*doc, profile);
      ASSERT_TRUE(rebuilt.isOk()) << rebuilt.status().toString();
      cut = std::move(rebuilt);
    }
    expectClosedAndOriented(*doc, *cut, "after step " + std::to_string(step), shown);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

TEST(CatmarkCut, LeavesFormAClosedOrientedSurfaceAfterEdits) {
  using namespace testing;
  Shown shown;
  uint32_t seed = 1;
  for (const PolyTestMesh& mesh :
       {quadCube(), withPolyJitter(quadTorus(7, 5), 0.05, 3),
        withRandomPolyTags(withPolyJitter(mixedPrism(6, false), 0.05, 5), 0.3, 0.1, 6)}) {
    checkCut(mesh, seed++, shown);
    if (HasFatalFailure()) return;
  }
  // Leaves of several levels side by side, so that edges carry finer points.
  EXPECT_GE(shown.leafLevels.size(), 3u);
  EXPECT_GT(shown.quadLeavesWithPoints, 0);
  std::printf("%lld leaves, %lld triangles, %lld quad leaves closing finer neighbours\n", shown.leaves,
              shown.triangles, shown.quadLeavesWithPoints);
}

}  // namespace
}  // namespace tessera
