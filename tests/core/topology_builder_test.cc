// The one builder of edges and ordered rings (core/topology/level_builder.h)
// and the one applier of tags and boundary rules (core/topology/tags.h), on
// small meshes whose edges, rings and rules are worked out by hand below
// (conventions of core/topology/level.h: face edge j joins corners j and
// j+1; rings counter-clockwise, a boundary ring from the boundary edge that
// leaves the vertex; edges numbered in order of first use).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/topology/level_builder.h"
#include "core/topology/tags.h"

namespace tessera::topology {
namespace {

FaceRows rows(int numVertices, const std::vector<std::vector<Index>>& faces) {
  FaceRows r;
  r.numVertices = numVertices;
  r.offsets.push_back(0);
  for (const auto& f : faces) {
    r.corners.insert(r.corners.end(), f.begin(), f.end());
    r.offsets.push_back(static_cast<Index>(r.corners.size()));
  }
  return r;
}

std::vector<Index> toVector(std::span<const Index> s) {
  return {s.begin(), s.end()};
}
std::vector<int> locals(const Level& level, Index v) {
  std::vector<int> out;
  for (Index k = level.ringOffsets[v]; k < level.ringOffsets[v + 1]; ++k)
    out.push_back(level.ringFaceLocal[k]);
  return out;
}

std::string errorOf(const Expected<Level>& r) {
  return r.isOk() ? std::string("ok") : r.status().message();
}

// A unit quad 0 (0,0), 1 (1,0), 2 (1,1), 3 (0,1) and a triangle on its
// right side with apex 4 (2, 0.5). The triangle runs the shared edge from 2
// to 1, the quad from 1 to 2. Edges by first use: quad 0-1 e0, 1-2 e1,
// 2-3 e2, 3-0 e3; triangle 1-4 e4, 4-2 e5, then 2-1 is e1 again.
TEST(TopologyBuilder, MixedQuadAndTriangleWithBoundaryRings) {
  auto built = buildLevel(rows(5, {{0, 1, 2, 3}, {1, 4, 2}}));
  ASSERT_TRUE(built.isOk()) << built.status().message();
  const Level& level = *built;
  EXPECT_EQ(level.numFaces(), 2);
  EXPECT_EQ(level.regularFaceSize, 0);  // mixed sizes keep their offsets
  EXPECT_EQ(level.maxFaceSize, 4);
  EXPECT_EQ(toVector(level.faceOffsets), (std::vector<Index>{0, 4, 7}));
  EXPECT_EQ(toVector(level.faceVerticesOf(1)), (std::vector<Index>{1, 4, 2}));
  ASSERT_EQ(level.numEdges(), 6);
  EXPECT_EQ(toVector(level.faceEdgesOf(0)), (std::vector<Index>{0, 1, 2, 3}));
  EXPECT_EQ(toVector(level.faceEdgesOf(1)), (std::vector<Index>{4, 5, 1}));
  EXPECT_EQ(level.edgeFaces[1], (std::array<Index, 2>{0, 1}));
  EXPECT_EQ(level.edgeFaceLocal[1], (std::array<LocalIndex, 2>{1, 2}));
  for (Index e : {0, 2, 3, 4, 5}) EXPECT_TRUE(level.isBoundaryEdge(e)) << "edge " << e;
  EXPECT_FALSE(level.isBoundaryEdge(1));
  EXPECT_TRUE(level.faceEdgeSides.empty());  // kept for levels of triangles only

  // Vertex 1 (1,0): neighbours 4 at 27 degrees, 2 at 90, 0 at 180. The
  // boundary edge leaving it is 1-4 in the triangle (corner 0), then the
  // quad (corner 1) across 1-2, then the boundary edge 0-1 with no face.
  EXPECT_EQ(toVector(level.ringEdgesOf(1)), (std::vector<Index>{4, 1, 0}));
  EXPECT_EQ(toVector(level.ringVerticesOf(1)), (std::vector<Index>{4, 2, 0}));
  EXPECT_EQ(toVector(level.ringFacesOf(1)), (std::vector<Index>{1, 0, kNoIndex}));
  EXPECT_EQ(locals(level, 1), (std::vector<int>{0, 1, 0}));
  // Vertex 2 (1,1): neighbours 3 at 180 degrees, 1 at 270, 4 at 333.
  EXPECT_EQ(toVector(level.ringEdgesOf(2)), (std::vector<Index>{2, 1, 5}));
  EXPECT_EQ(toVector(level.ringVerticesOf(2)), (std::vector<Index>{3, 1, 4}));
  EXPECT_EQ(toVector(level.ringFacesOf(2)), (std::vector<Index>{0, 1, kNoIndex}));
  EXPECT_EQ(locals(level, 2), (std::vector<int>{2, 2, 0}));
  // Vertex 0, a corner of the quad alone: the boundary edge 0-1 leaves it.
  EXPECT_EQ(toVector(level.ringVerticesOf(0)), (std::vector<Index>{1, 3}));
  EXPECT_EQ(level.numRingFaces(0), 1);
  EXPECT_EQ(level.maxValence, 3);
}

// Boundary rules on the same mesh: every edge but the shared one is
// infinitely sharp; a vertex on two sharp edges follows the crease rule, and
// with kEdgeAndCorner a boundary vertex of one face is a corner.
TEST(TopologyBuilder, TagsAndBoundaryRules) {
  for (auto boundary : {BoundaryInterpolation::kEdgeOnly, BoundaryInterpolation::kEdgeAndCorner}) {
    auto built = buildLevel(rows(5, {{0, 1, 2, 3}, {1, 4, 2}}));
    ASSERT_TRUE(built.isOk());
    Level level = std::move(*built);
    const std::vector<Crease> creases = {{2, 1, 2.5f}};
    ASSERT_TRUE(applyTags(creases, {}, boundary, level).isOk());
    EXPECT_EQ(level.edgeSharpness[1], 2.5f);
    for (Index e : {0, 2, 3, 4, 5}) EXPECT_EQ(level.edgeSharpness[e], kSharpnessInfinite);
    // Vertices 1 and 2 meet three sharp edges: corners by the edge count.
    EXPECT_EQ(level.vertexRules[1], VertexRule::kCorner);
    EXPECT_EQ(level.vertexRules[2], VertexRule::kCorner);
    const bool corners = boundary == BoundaryInterpolation::kEdgeAndCorner;
    for (Index v : {0, 3, 4}) {
      EXPECT_EQ(level.vertexRules[v], corners ? VertexRule::kCorner : VertexRule::kCrease) << "vertex " << v;
      EXPECT_EQ(level.vertexSharpness[v], corners ? kSharpnessInfinite : kSharpnessSmooth);
    }
  }
}

// Four triangles around vertex 0, closed: an interior ring from the
// lowest-numbered face. Edges by first use: 0-1 e0, 1-2 e1, 2-0 e2, 2-3 e3,
// 3-0 e4, 3-4 e5, 4-0 e6, 4-1 e7.
TEST(TopologyBuilder, TrianglesKeepTheStrideAndEdgeSides) {
  auto built = buildLevel(rows(5, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}}));
  ASSERT_TRUE(built.isOk()) << built.status().message();
  const Level& level = *built;
  EXPECT_TRUE(level.allTriangles());
  EXPECT_TRUE(level.faceOffsets.empty());  // face f is corners 3f..3f+2
  ASSERT_EQ(level.numFaces(), 4);
  for (Index f = 0; f < 4; ++f) {
    EXPECT_EQ(toVector(level.triangleVertices(f)), toVector(level.faceVerticesOf(f)));
    EXPECT_EQ(toVector(level.triangleEdges(f)), toVector(level.faceEdgesOf(f)));
  }
  EXPECT_EQ(toVector(level.triangleEdges(3)), (std::vector<Index>{6, 7, 0}));
  EXPECT_FALSE(level.isBoundaryVertex(0));
  EXPECT_EQ(toVector(level.ringEdgesOf(0)), (std::vector<Index>{0, 2, 4, 6}));
  EXPECT_EQ(toVector(level.ringVerticesOf(0)), (std::vector<Index>{1, 2, 3, 4}));
  EXPECT_EQ(toVector(level.ringFacesOf(0)), (std::vector<Index>{0, 1, 2, 3}));
  EXPECT_EQ(locals(level, 0), (std::vector<int>{0, 0, 0, 0}));
  // Faces 1..3 come second on their edge 0 (2-0, 3-0, 4-0), face 3 also on
  // its edge 2 (1-0): they run those edges backwards.
  const std::vector<int> sides(level.faceEdgeSides.begin(), level.faceEdgeSides.end());
  EXPECT_EQ(sides, (std::vector<int>{0b000, 0b001, 0b001, 0b101}));
}

TEST(TopologyBuilder, ErrorsNameTheEdgeFaceOrVertex) {
  // Three triangles on edge 0-1: the third (face 2, running 1 to 0) is one too many.
  EXPECT_EQ(errorOf(buildLevel(rows(5, {{0, 1, 2}, {1, 0, 3}, {1, 0, 4}}))),
            "edge 1-0 is non-manifold: used by faces 0, 1 and 2");
  EXPECT_EQ(errorOf(buildLevel(rows(4, {{0, 1, 2, 3}, {0, 1, 3}}))),
            "faces 0 and 1 are inconsistently oriented across edge 0-1");
  // A bow tie: two fans meet at vertex 0.
  EXPECT_EQ(errorOf(buildLevel(rows(5, {{0, 1, 2}, {0, 3, 4}}))),
            "vertex 0 is non-manifold: its faces do not form one fan");
  EXPECT_NE(errorOf(buildLevel(rows(5, {{0, 1, 2, 3}}))).find("vertex 4 is not used"), std::string::npos);
  EXPECT_NE(errorOf(buildLevel(rows(4, {{0, 1, 2}, {2, 1, 3, 3}}))).find("face 1 uses vertex 3 twice"),
            std::string::npos);
  EXPECT_NE(errorOf(buildLevel(rows(3, {{0, 1, -1}}))).find("face 0 names vertex -1"), std::string::npos);
  EXPECT_NE(errorOf(buildLevel(rows(3, {}))).find("mesh is empty"), std::string::npos);

  auto built = buildLevel(rows(4, {{0, 1, 2}, {0, 2, 3}}));
  ASSERT_TRUE(built.isOk());
  const std::vector<Crease> diagonal = {{0, 2, 1.0f}, {1, 3, 1.0f}};
  const Status missing = applyTags(diagonal, {}, BoundaryInterpolation::kEdgeOnly, *built);
  EXPECT_NE(missing.message().find("crease 1: edge 1-3 does not exist"), std::string::npos)
      << missing.message();
  const std::vector<float> tooFew = {1.0f};
  EXPECT_FALSE(applyTags({}, tooFew, BoundaryInterpolation::kEdgeOnly, *built).isOk());
}

}  // namespace
}  // namespace tessera::topology
