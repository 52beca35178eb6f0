// The one topology builder (core/topology/level_builder.h) against
// OpenSubdiv's Far level 0 of the same faces: the same edges in the same
// order, the same edge faces and, for every vertex, the same ordered ring of
// edges, faces and corners (Vtr::Level::orderVertexFacesAndEdges). Triangle
// meshes go through the Loop entry (buildBaseLevel) against SCHEME_LOOP,
// polygon meshes through the polygon entry (buildPolyLevel) against
// SCHEME_CATMARK.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/catmark/polygon_level.h"
#include "core/loop/level_builder.h"
#include "oracle/osd_adapter.h"
#include "oracle/osd_catmark_reference.h"
#include "support/polygon_meshes.h"
#include "support/procedural_meshes.h"

namespace tessera::oracle {
namespace {

namespace Far = OpenSubdiv::Far;

template <typename A, typename B>
std::vector<int> asInts(const A& array, B size) {
  std::vector<int> out;
  for (int i = 0; i < static_cast<int>(size); ++i) out.push_back(static_cast<int>(array[i]));
  return out;
}

void expectSameTopology(const Level& ours, const Far::TopologyLevel& far, const std::string& name) {
  ASSERT_EQ(ours.numVertices, far.GetNumVertices()) << name;
  ASSERT_EQ(ours.numFaces(), far.GetNumFaces()) << name;
  ASSERT_EQ(ours.numEdges(), far.GetNumEdges()) << name;
  for (Index f = 0; f < ours.numFaces(); ++f) {
    const auto fv = far.GetFaceVertices(f);
    const auto fe = far.GetFaceEdges(f);
    EXPECT_EQ(asInts(ours.faceVerticesOf(f), ours.faceSize(f)), asInts(fv, fv.size()))
        << name << " face " << f;
    EXPECT_EQ(asInts(ours.faceEdgesOf(f), ours.faceSize(f)), asInts(fe, fe.size())) << name << " face " << f;
  }
  for (Index e = 0; e < ours.numEdges(); ++e) {
    const auto ev = far.GetEdgeVertices(e);
    EXPECT_EQ(asInts(ours.edgeVertices[e], 2), asInts(ev, 2)) << name << " edge " << e;
    const auto ef = far.GetEdgeFaces(e);
    const auto el = far.GetEdgeFaceLocalIndices(e);
    const int faces = ours.isBoundaryEdge(e) ? 1 : 2;
    EXPECT_EQ(asInts(ours.edgeFaces[e], faces), asInts(ef, ef.size())) << name << " edge " << e;
    EXPECT_EQ(asInts(ours.edgeFaceLocal[e], faces), asInts(el, el.size())) << name << " edge " << e;
  }
  for (Index v = 0; v < ours.numVertices; ++v) {
    const auto ve = far.GetVertexEdges(v);
    const auto vf = far.GetVertexFaces(v);
    const auto vl = far.GetVertexFaceLocalIndices(v);
    EXPECT_EQ(ours.isBoundaryVertex(v), far.IsVertexBoundary(v)) << name << " vertex " << v;
    EXPECT_EQ(asInts(ours.ringEdgesOf(v), ours.valence(v)), asInts(ve, ve.size())) << name << " vertex " << v;
    const int faces = ours.numRingFaces(v);
    EXPECT_EQ(asInts(ours.ringFacesOf(v), faces), asInts(vf, vf.size())) << name << " vertex " << v;
    EXPECT_EQ(asInts(ours.ringFaceLocal.data() + ours.ringOffsets[v], faces), asInts(vl, vl.size()))
        << name << " vertex " << v;
    for (int k = 0; k < ours.valence(v); ++k) {
      const auto far_ends = far.GetEdgeVertices(ve[k]);
      EXPECT_EQ(ours.ringVerticesOf(v)[k], far_ends[0] == v ? far_ends[1] : far_ends[0])
          << name << " vertex " << v;
    }
  }
}

TEST(TopologyBuilderOracle, TriangleMeshesHaveOpenSubdivsLoopLevel) {
  const std::vector<testing::TestMesh> meshes = {testing::icosahedron(), testing::doubleTorus(),
                                                 testing::openGrid(5, 4), testing::diskWithPole(9),
                                                 testing::withRandomFlips(testing::torus(8, 6), 20, 7)};
  for (const auto& mesh : meshes) {
    auto ours = buildBaseLevel(mesh.topology, {});
    ASSERT_TRUE(ours.isOk()) << mesh.name << ": " << ours.status().message();
    EXPECT_TRUE(ours->allTriangles()) << mesh.name;
    const OsdInput input(mesh.topology);
    auto far = createOsdRefiner(input, {}, 0, true);
    expectSameTopology(*ours, far->GetLevel(0), mesh.name);
  }
}

TEST(TopologyBuilderOracle, PolygonMeshesHaveOpenSubdivsCatmarkLevel) {
  const std::vector<testing::PolyTestMesh> meshes = {testing::quadCube(), testing::mixedPrism(6, false),
                                                     testing::mixedPrism(7, true), testing::quadGrid(4, 3)};
  for (const auto& mesh : meshes) {
    auto ours = buildPolyLevel(mesh.topology, {});
    ASSERT_TRUE(ours.isOk()) << mesh.name << ": " << ours.status().message();
    const OsdPolyInput input(mesh.topology);
    auto far = createOsdQuadRefiner(input, schemes::QuadScheme::kCatmullClark, {}, 0, true);
    expectSameTopology(*ours, far->GetLevel(0), mesh.name);
  }
}

}  // namespace
}  // namespace tessera::oracle
