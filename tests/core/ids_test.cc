// Canonical element ids: text round trips, errors, and agreement of the id
// arithmetic with the uniform refinement that defines it.
#include <gtest/gtest.h>

#include "core/hierarchy/ids.h"
#include "core/loop/loop_refiner.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

TEST(ElementIds, PrintAndParseRoundTrip) {
  for (VertexId id : {VertexId(0, 0), VertexId(3, 1234), VertexId(63, VertexId::kIndexMask)}) {
    auto back = parseVertexId(id.toString());
    ASSERT_TRUE(back.isOk()) << back.status().toString();
    EXPECT_EQ(*back, id);
  }
  EXPECT_EQ(EdgeId(2, 55).toString(), "e2:55");
  EXPECT_EQ(parseFaceId("f4:1023").value(), FaceId(4, 1023));
  EXPECT_EQ(VertexId::fromPacked(VertexId(5, 77).packed()), VertexId(5, 77));
}

TEST(ElementIds, ParseRejectsMalformedText) {
  for (const char* bad : {"", "v", "v3", "v3:", "v:12", "x3:12", "v3:12x", "v-1:4", "v64:1", "v3:-1",
                          "v3:1:2", "e3:1", "v 3:1"}) {
    auto id = parseVertexId(bad);
    EXPECT_FALSE(id.isOk()) << bad;
    if (!id.isOk()) {
      EXPECT_NE(id.status().message().find("vertex id"), std::string::npos) << bad;
    }
  }
  EXPECT_FALSE(parseEdgeId("v1:2").isOk());
}

TEST(ElementIds, CountsMatchUniformRefinement) {
  auto mesh = testing::withRandomFlips(testing::torus(7, 5), 10, 2);
  auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = 4});
  ASSERT_TRUE(refiner.isOk());
  const Level& base = refiner->level(0);
  LevelCounts counts(base.numVertices, base.numEdges(), base.numFaces(), 4);
  for (int l = 0; l <= 4; ++l) {
    EXPECT_EQ(counts.vertices(l), static_cast<uint64_t>(refiner->level(l).numVertices));
    EXPECT_EQ(counts.edges(l), static_cast<uint64_t>(refiner->level(l).numEdges()));
    EXPECT_EQ(counts.faces(l), static_cast<uint64_t>(refiner->level(l).numFaces()));
  }
}

TEST(ElementIds, ParentAndChildRelationsMatchTheRefinedTopology) {
  auto mesh = testing::openGrid(4, 3);
  auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = 3});
  ASSERT_TRUE(refiner.isOk());
  const Level& base = refiner->level(0);
  LevelCounts counts(base.numVertices, base.numEdges(), base.numFaces(), 3);
  for (int l = 0; l < 3; ++l) {
    const Level& parent = refiner->level(l);
    const Level& child = refiner->level(l + 1);
    for (int e = 0; e < parent.numEdges(); ++e) {
      const VertexId mid = counts.childOf(EdgeId(l, e));
      EXPECT_FALSE(counts.isVertexChild(mid));
      EXPECT_EQ(counts.parentEdge(mid), EdgeId(l, e));
      EXPECT_EQ(counts.birthLevel(mid), l + 1);
      // The midpoint is an end of both halves of its parent edge.
      for (int half : {2 * e, 2 * e + 1}) {
        const auto& ev = child.edgeVertices[half];
        EXPECT_TRUE(ev[0] == static_cast<int>(mid.index()) || ev[1] == static_cast<int>(mid.index()));
      }
    }
    for (int f = 0; f < parent.numFaces(); ++f) {
      for (int k = 0; k < 4; ++k) {
        const FaceId c = counts.childFace(FaceId(l, f), k);
        EXPECT_EQ(counts.parentFace(c), FaceId(l, f));
        EXPECT_EQ(counts.baseFace(c), counts.baseFace(FaceId(l, f)));
      }
      // Corner k of face f is the corner k of child face 4f+k: same vertex id.
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(child.triangleVertices(4 * f + k)[k], parent.triangleVertices(f)[k]);
      }
    }
  }
  // A face's ancestor at each level is its parent's parent and so on.
  for (int f = 0; f < refiner->level(3).numFaces(); ++f) {
    FaceId up(3, static_cast<uint64_t>(f));
    for (int k = 3; k >= 0; --k) {
      EXPECT_EQ(counts.ancestorAt(FaceId(3, static_cast<uint64_t>(f)), k), up);
      if (k > 0) up = counts.parentFace(up);
    }
  }
}

TEST(ElementIds, CheckNamesTheProblem) {
  LevelCounts counts(10, 24, 16, 2);
  EXPECT_TRUE(counts.check(VertexId(2, counts.vertices(2) - 1)).isOk());
  Status s = counts.check(VertexId(3, 0));
  EXPECT_NE(s.message().find("above the maximum level 2"), std::string::npos) << s.message();
  s = counts.check(EdgeId(1, counts.edges(1)));
  EXPECT_NE(s.message().find("e1:"), std::string::npos) << s.message();
  EXPECT_EQ(s.code(), ErrorCode::kNotFound);
}

}  // namespace
}  // namespace tessera
