// Naming an edge by its two end vertices (hierarchy/incidence.h), checked
// against the uniform refinement of core/loop, whose topology the oracle
// suite compares with OpenSubdiv: every edge of every level is found from its
// ends in either order, and every other pair of vertices is refused with a
// message naming both.
#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "core/document/document.h"
#include "core/hierarchy/incidence.h"
#include "core/loop/loop_refiner.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

using testing::TestMesh;

bool names(const Status& status, VertexId a, VertexId b) {
  return status.message().find(a.toString()) != std::string::npos &&
         status.message().find(b.toString()) != std::string::npos;
}

TEST(EdgeLookup, EveryEdgeOfEveryLevelIsFoundFromItsEnds) {
  for (const TestMesh& mesh :
       {testing::icosahedron(), testing::openGrid(4, 3), testing::diskWithPole(7),
        testing::withRandomFlips(testing::torus(6, 5), 8, 3), testing::doubleTorus()}) {
    auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = 3});
    ASSERT_TRUE(refiner.isOk()) << refiner.status().message();
    const Level& base = refiner->level(0);
    const LevelCounts counts(base.numVertices, base.numEdges(), base.numFaces(), 3);
    for (int l = 0; l <= 3; ++l) {
      const Level& level = refiner->level(l);
      for (Index e = 0; e < level.numEdges(); ++e) {
        const EdgeId id(l, static_cast<uint64_t>(e));
        const auto ends = edgeEnds(base, counts, id);
        ASSERT_EQ(ends[0], VertexId(l, level.edgeVertices[e][0])) << mesh.name << " " << id.toString();
        ASSERT_EQ(ends[1], VertexId(l, level.edgeVertices[e][1])) << mesh.name << " " << id.toString();
        for (const auto& [a, b] : {std::pair{ends[0], ends[1]}, std::pair{ends[1], ends[0]}}) {
          auto found = edgeBetween(base, counts, a, b);
          ASSERT_TRUE(found.isOk()) << mesh.name << " " << id.toString() << ": " << found.status().message();
          ASSERT_EQ(*found, id) << mesh.name << " " << a.toString() << " " << b.toString();
        }
      }
    }
  }
}

TEST(EdgeLookup, EveryPairWithoutAnEdgeIsRefusedNamingBothIds) {
  for (const TestMesh& mesh : {testing::icosahedron(), testing::openGrid(3, 2)}) {
    auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = 2});
    ASSERT_TRUE(refiner.isOk());
    const Level& base = refiner->level(0);
    const LevelCounts counts(base.numVertices, base.numEdges(), base.numFaces(), 2);
    for (int l = 0; l <= 2; ++l) {
      const Level& level = refiner->level(l);
      std::set<std::pair<Index, Index>> joined;
      for (const auto& ev : level.edgeVertices)
        joined.insert({std::min(ev[0], ev[1]), std::max(ev[0], ev[1])});
      size_t refused = 0;
      for (Index v = 0; v < level.numVertices; ++v) {
        for (Index w = v + 1; w < level.numVertices; ++w) {
          if (joined.count({v, w})) continue;
          const VertexId a(l, static_cast<uint64_t>(v)), b(l, static_cast<uint64_t>(w));
          auto found = edgeBetween(base, counts, a, b);
          ASSERT_FALSE(found.isOk()) << mesh.name << " " << a.toString() << " " << b.toString() << " gave "
                                     << found->toString();
          ASSERT_EQ(found.status().code(), ErrorCode::kInvalidArgument);
          ASSERT_TRUE(names(found.status(), a, b)) << found.status().message();
          ++refused;
        }
      }
      EXPECT_GT(refused, joined.size()) << mesh.name << " level " << l;
    }
  }
}

TEST(EdgeLookup, DocumentRefusesMixedLevelsUnknownIdsAndOneVertexTwice) {
  const TestMesh mesh = testing::icosahedron();
  auto doc = Document::create(mesh.topology, mesh.points, {.loop = {}, .maxLevel = 3});
  ASSERT_TRUE(doc.isOk());
  // A base edge, and a half of it two levels down.
  const Level& base = doc->hierarchy().level(0).mesh;
  const VertexId a(0, static_cast<uint64_t>(base.edgeVertices[0][0]));
  const VertexId b(0, static_cast<uint64_t>(base.edgeVertices[0][1]));
  EXPECT_EQ(*doc->edgeBetween(a, b), EdgeId(0, 0));
  const VertexId middle(1, doc->counts().vertices(0));  // the vertex on e0:0
  EXPECT_EQ(*doc->edgeBetween(VertexId(1, a.index()), middle), EdgeId(1, 0));
  EXPECT_FALSE(doc->edgeBetween(VertexId(2, middle.index()), VertexId(2, b.index())).isOk())
      << "a level-1 half is not a level-2 edge";

  auto mixed = doc->edgeBetween(a, middle);
  ASSERT_FALSE(mixed.isOk());
  EXPECT_EQ(mixed.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_TRUE(names(mixed.status(), a, middle)) << mixed.status().message();

  const VertexId unknown(1, doc->counts().vertices(1));
  auto missing = doc->edgeBetween(middle, unknown);
  ASSERT_FALSE(missing.isOk());
  EXPECT_EQ(missing.status().code(), ErrorCode::kNotFound);
  EXPECT_NE(missing.status().message().find(unknown.toString()), std::string::npos)
      << missing.status().message();
  auto tooDeep = doc->edgeBetween(VertexId(4, 0), VertexId(4, 1));
  ASSERT_FALSE(tooDeep.isOk());
  EXPECT_EQ(tooDeep.status().code(), ErrorCode::kNotFound);

  auto same = doc->edgeBetween(a, a);
  ASSERT_FALSE(same.isOk());
  EXPECT_EQ(same.status().code(), ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace tessera
