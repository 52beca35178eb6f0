// The coarse morph stream on its own (server/document/morph_control.h,
// docs/PROTOCOL.md §14): the base control points at t, the topology and
// rules on request, and a time outside the morph refused naming the
// document.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/document/document.h"
#include "server/document/morph_control.h"
#include "support/test_meshes.h"

namespace tessera::server {
namespace {

Document cube() {
  auto doc = testing::cubeDocument(2);
  EXPECT_TRUE(doc.isOk()) << doc.status().message();
  return std::move(*doc);
}

// The cube morphing into itself scaled by 3.
KeyedDocument growingCube() {
  KeyedDocument doc(cube());
  std::vector<Vec3> points = doc.key0().basePoints();
  for (Vec3& p : points) p = 3.0 * p;
  EXPECT_TRUE(doc.addKey(points).isOk());
  return doc;
}

wire::GetMorphControl at(double t, bool withTopology = false) {
  wire::GetMorphControl request;
  request.set_t(t);
  request.set_with_topology(withTopology);
  return request;
}

TEST(MorphControl, ThePointsAtTheTime) {
  KeyedDocument doc = growingCube();
  auto m = morphControlMessage(doc, 7, 12, 3, at(0.5));
  ASSERT_TRUE(m.isOk()) << m.status().message();
  ASSERT_TRUE(m->has_morph_control());
  const wire::MorphControl& c = m->morph_control();
  EXPECT_EQ(c.client_seq(), 3u);
  EXPECT_EQ(c.document_id(), 7u);
  EXPECT_EQ(c.version(), 12u);
  EXPECT_EQ(c.t(), 0.5);
  const std::vector<Vec3>& key0 = doc.key0().basePoints();
  ASSERT_EQ(c.points_size(), static_cast<int>(3 * key0.size()));
  for (size_t v = 0; v < key0.size(); ++v) {
    for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(c.points(static_cast<int>(3 * v) + k), 2.0 * key0[v][k]);
  }
  EXPECT_EQ(c.triangles_size(), 0) << "no topology unless asked";
}

TEST(MorphControl, WithTopologyAClientCanSubdivideItself) {
  KeyedDocument doc = growingCube();
  auto m = morphControlMessage(doc, 7, 12, 3, at(0.25, /*withTopology=*/true));
  ASSERT_TRUE(m.isOk()) << m.status().message();
  const wire::MorphControl& c = m->morph_control();
  EXPECT_EQ(c.triangles_size(), 3 * 12) << "the cube's twelve triangles";
  EXPECT_EQ(c.max_level(), 2u);
  EXPECT_EQ(c.crease_sharpness_size() * 2, c.crease_vertices_size());
  EXPECT_TRUE(c.image_from().empty() && c.image_to().empty()) << "a 3D morph has no images";
}

TEST(MorphControl, ATimeOutsideTheMorphIsRefusedNamingTheDocument) {
  KeyedDocument doc = growingCube();
  auto m = morphControlMessage(doc, 7, 12, 3, at(1.5));
  ASSERT_FALSE(m.isOk());
  EXPECT_EQ(m.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(m.status().message().find("morph control of document 7"), std::string::npos)
      << m.status().message();

  KeyedDocument still(cube());
  EXPECT_FALSE(morphControlMessage(still, 7, 12, 3, at(0.5)).isOk()) << "one key: no morph";
}

}  // namespace
}  // namespace tessera::server
