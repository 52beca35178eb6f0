// The control cage through the service (GetCage, docs/PROTOCOL.md section
// 15): the real tessera-server (127.0.0.1, real store) answers a level's
// polygons of a Catmull-Clark document as the model's quads and its
// subdivision's quads, and of a Loop document as triangles; the faces do not
// change with an edit, only the version; a level beyond the document's, one
// above --max-triangles and an unopened document get a Reject that names
// them, and the session carries on.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "client/lib/session.h"
#include "core/schemes/polygon_reader.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::Session;
using testing::ServerProcess;

wire::ClientMessage getCage(uint64_t doc, uint32_t level) {
  wire::ClientMessage m;
  m.mutable_get_cage()->set_document_id(doc);
  m.mutable_get_cage()->set_level(level);
  return m;
}

std::vector<std::vector<uint64_t>> facesOf(const wire::Cage& cage) {
  std::vector<std::vector<uint64_t>> faces;
  int at = 0;
  for (uint32_t n : cage.face_sizes()) {
    faces.emplace_back(cage.vertices().begin() + at, cage.vertices().begin() + at + static_cast<int>(n));
    at += static_cast<int>(n);
  }
  EXPECT_EQ(at, cage.vertices_size());
  return faces;
}

// Every edge of a closed surface is a side of two faces, run once each way.
void expectClosedAndOriented(const std::vector<std::vector<uint64_t>>& faces) {
  std::map<std::pair<uint64_t, uint64_t>, int> directed;
  for (const auto& f : faces)
    for (size_t k = 0; k < f.size(); ++k) ++directed[{f[k], f[(k + 1) % f.size()]}];
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " runs twice the same way";
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u)
        << "edge " << edge.first << "-" << edge.second << " has one face";
  }
}

// tests/data's cube of six quads as a Catmull-Clark document of max level
// 4, created and opened by `admin`: its id, or 0 with the failure recorded.
uint64_t createAndOpenQuadCube(Session& admin) {
  wire::ClientMessage create = testing::createDocument(
      "quads", testing::fileBytes(testing::sourceTestDataPath("good/cube_quads.obj")), "", 4);
  create.mutable_create_document()->set_file_name("cube_quads.obj");
  auto created = admin.call(create, 30);
  if (!created.isOk() || !created->has_ack()) {
    ADD_FAILURE() << "create: " << (created.isOk() ? created->DebugString() : created.status().message());
    return 0;
  }
  const uint64_t doc = created->ack().document_id();
  auto opened = admin.call(testing::openDocument(doc), 30);
  if (!opened.isOk() || !opened->has_ack()) {
    ADD_FAILURE() << "open: " << (opened.isOk() ? opened->DebugString() : opened.status().message());
    return 0;
  }
  return doc;
}

TEST(ServerControlCage, LevelsArriveAsTheirPolygonsAndBadRequestsAreRefusedByName) {
  const std::string dir = testing::makeTempDir("tessera-cage");
  // 6 x 4^4 = 1,536 faces at level 4: above this bound, level 3's 384 below.
  auto server = ServerProcess::start(dir + "/data", {"--max-triangles", "1000"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());

  const std::string cubePath = testing::sourceTestDataPath("good/cube_quads.obj");
  const uint64_t doc = createAndOpenQuadCube(**admin);
  ASSERT_NE(doc, 0u);

  // Level 0: the file's six quads, in its order (OBJ counts from 1).
  auto base = (*admin)->call(getCage(doc, 0), 30);
  ASSERT_TRUE(base.isOk() && base->has_cage()) << base->DebugString();
  auto read = schemes::importPolygonMesh(cubePath, "");
  ASSERT_TRUE(read.isOk());
  const auto baseFaces = facesOf(base->cage());
  ASSERT_EQ(baseFaces.size(), 6u);
  for (int f = 0; f < 6; ++f) {
    const std::vector<uint64_t> given(read->topology.indices.begin() + read->topology.faceOffsets[f],
                                      read->topology.indices.begin() + read->topology.faceOffsets[f + 1]);
    EXPECT_EQ(baseFaces[f], given) << "base face " << f;
  }
  expectClosedAndOriented(baseFaces);

  // Level 1: each quad split in four, over the 8 + 12 + 6 vertices of level 1.
  auto one = (*admin)->call(getCage(doc, 1), 30);
  ASSERT_TRUE(one.isOk() && one->has_cage()) << one->DebugString();
  const auto levelOne = facesOf(one->cage());
  ASSERT_EQ(levelOne.size(), 24u);
  std::set<uint64_t> used;
  for (const auto& f : levelOne) {
    EXPECT_EQ(f.size(), 4u);
    used.insert(f.begin(), f.end());
  }
  EXPECT_EQ(used.size(), 26u);
  EXPECT_EQ(*used.rbegin(), 25u);
  expectClosedAndOriented(levelOne);

  // An edit moves points, never faces: the same cage at a newer version.
  auto moved = (*admin)->call(testing::moveVertex(doc, VertexId(1, 3).packed(), 0.2, 0.9, 0.1), 30);
  ASSERT_TRUE(moved.isOk() && moved->has_ack()) << moved->DebugString();
  auto after = (*admin)->call(getCage(doc, 1), 30);
  ASSERT_TRUE(after.isOk() && after->has_cage());
  EXPECT_EQ(facesOf(after->cage()), levelOne);
  EXPECT_EQ(after->cage().version(), moved->ack().version());
  EXPECT_GT(after->cage().version(), one->cage().version());

  // Refusals name what was asked and why; the session carries on.
  auto beyond = (*admin)->call(getCage(doc, 5), 30);
  ASSERT_TRUE(beyond.isOk() && beyond->has_reject()) << beyond->DebugString();
  EXPECT_NE(beyond->reject().message().find("level 5 is outside 0..4"), std::string::npos)
      << beyond->reject().message();
  auto large = (*admin)->call(getCage(doc, 4), 30);
  ASSERT_TRUE(large.isOk() && large->has_reject()) << large->DebugString();
  EXPECT_EQ(large->reject().reason(), wire::REJECT_REASON_LIMIT_EXCEEDED);
  EXPECT_NE(large->reject().message().find("1536 faces"), std::string::npos) << large->reject().message();
  EXPECT_NE(large->reject().message().find("--max-triangles"), std::string::npos)
      << large->reject().message();
  auto unopened = (*admin)->call(getCage(doc + 100, 0), 30);
  ASSERT_TRUE(unopened.isOk() && unopened->has_reject()) << unopened->DebugString();
  auto three = (*admin)->call(getCage(doc, 3), 30);
  ASSERT_TRUE(three.isOk() && three->has_cage()) << three->DebugString();
  EXPECT_EQ(three->cage().face_sizes_size(), 384);

  // A Loop document's levels are triangles: four per base triangle per level.
  wire::ClientMessage loop = testing::createDocument(
      "tetra", testing::fileBytes(testing::sourceTestDataPath("good/tetra.obj")), "", 3);
  auto loopCreated = (*admin)->call(loop, 30);
  ASSERT_TRUE(loopCreated.isOk() && loopCreated->has_ack()) << loopCreated->DebugString();
  const uint64_t tetra = loopCreated->ack().document_id();
  ASSERT_TRUE((*admin)->call(testing::openDocument(tetra), 30)->has_ack());
  auto triangles = (*admin)->call(getCage(tetra, 2), 30);
  ASSERT_TRUE(triangles.isOk() && triangles->has_cage()) << triangles->DebugString();
  const auto loopFaces = facesOf(triangles->cage());
  EXPECT_EQ(loopFaces.size(), 4u * 16u);
  for (const auto& f : loopFaces) EXPECT_EQ(f.size(), 3u);
  expectClosedAndOriented(loopFaces);
}

// A reply built on the document's queue that would not fit in a frame (a
// cage or an export of a fine level under a small --max-frame-bytes) is
// refused with the reason and what to ask instead, and the session goes on:
// a coarser level that fits still arrives.
TEST(ServerControlCage, RepliesOverTheFrameLimitAreRefusedAndACoarserLevelStillArrives) {
  const std::string dir = testing::makeTempDir("tessera-cage-frame");
  auto server = ServerProcess::start(dir + "/data", {"--max-frame-bytes", "2048"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());
  const uint64_t doc = createAndOpenQuadCube(**admin);
  ASSERT_NE(doc, 0u);

  // Level 3: 384 quads over 386 vertices, more than 2,048 bytes.
  auto cage = (*admin)->call(getCage(doc, 3), 30);
  ASSERT_TRUE(cage.isOk() && cage->has_reject()) << cage->DebugString();
  EXPECT_NE(cage->reject().message().find(
                "control cage of level 3 exceeds the frame limit; ask for a coarser level"),
            std::string::npos)
      << cage->reject().message();
  wire::ClientMessage exported;
  exported.mutable_export_document()->set_document_id(doc);
  exported.mutable_export_document()->set_level(3);
  auto glb = (*admin)->call(exported, 30);
  ASSERT_TRUE(glb.isOk() && glb->has_reject()) << glb->DebugString();
  EXPECT_NE(glb->reject().message().find("the export exceeds the frame limit"), std::string::npos)
      << glb->reject().message();

  auto one = (*admin)->call(getCage(doc, 1), 30);
  ASSERT_TRUE(one.isOk() && one->has_cage()) << one->DebugString();
  EXPECT_EQ(one->cage().face_sizes_size(), 24);
}

}  // namespace
}  // namespace tessera
