// Catmull-Clark documents through the service: the real tessera-server
// (127.0.0.1, real store) creates a document of a quad model with the
// scheme its faces call for, says so in its Ack, and refuses what a
// Catmull-Clark document cannot take by name; an editor's moves (to a limit
// position and by offset), crease, batch and undo reach a viewer as region
// deltas whose triangles and vertex ids are those of a local document given
// the same edits, within the stream's quantization; a late joiner, and a
// viewer after a restart (journal replay), see the same surface bit for bit.
#include <gtest/gtest.h>

#include <cstdio>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "core/document/document.h"
#include "core/schemes/polygon_reader.h"
#include "core/tessellation/tessellation.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/region_checks.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::ServerProcess;

constexpr int kMaxLevel = 4;
const LodProfile kProfile{.baseLevel = 1, .maxLevel = kMaxLevel, .angleThresholdDegrees = 15};

std::string quadCubePath() {
  return testing::sourceTestDataPath("good/cube_quads.obj");
}

wire::ClientMessage createQuadCube(wire::SubdivisionScheme scheme, bool triangulate = false) {
  wire::ClientMessage m = testing::createDocument("quads", testing::fileBytes(quadCubePath()), "", kMaxLevel);
  m.mutable_create_document()->set_file_name("cube_quads.obj");
  m.mutable_create_document()->set_scheme(scheme);
  m.mutable_create_document()->set_triangulate(triangulate);
  return m;
}

void readUntil(Session& s, DocumentView& view, uint64_t version) {
  for (int i = 0; i < 400 && (!view.ready() || view.version() < version); ++i) {
    auto m = s.receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    Status ok = view.apply(*m);
    ASSERT_TRUE(ok.isOk()) << ok.message();
  }
  ASSERT_TRUE(view.ready());
  ASSERT_EQ(view.version(), version);
  ASSERT_TRUE(view.verifySurface().isOk()) << view.verifySurface().message();
}

// The streamed regions hold the local tessellation's: the same region ids,
// the same triangles over the same vertex ids, positions within `tolerance`
// (the stream's quantization).
void expectStreamedIsLocal(const DocumentView& streamed, const Tessellation& local, double tolerance,
                           const std::string& when) {
  ASSERT_EQ(streamed.regions().size(), local.regions().size()) << when;
  double worst = 0;
  for (const auto& [id, mesh] : local.regions()) {
    ASSERT_EQ(streamed.regions().count(id), 1u) << when << ": region " << id;
    const RegionMesh& got = streamed.regions().at(id);
    ASSERT_EQ(testing::trianglesOverIds(got), testing::trianglesOverIds(mesh)) << when << ": region " << id;
    std::map<uint64_t, Vec3> expected;
    for (size_t v = 0; v < mesh.positions.size(); ++v) expected[mesh.vertexIds[v]] = mesh.positions[v];
    for (size_t v = 0; v < got.positions.size(); ++v)
      worst = std::max(worst, (got.positions[v] - expected.at(got.vertexIds[v])).norm());
  }
  EXPECT_LE(worst, tolerance) << when;
  std::printf("%s: %zu regions, streamed positions within %.3g of the local document's\n", when.c_str(),
              local.regions().size(), worst);
}

// Two viewers decoded the same surface: the same regions, triangles over
// the same ids, and each id's position bit for bit.
void expectSameDecodedRegions(const DocumentView& a, const DocumentView& b, const std::string& when) {
  ASSERT_EQ(a.regions().size(), b.regions().size()) << when;
  for (const auto& [id, mesh] : b.regions()) {
    ASSERT_EQ(a.regions().count(id), 1u) << when << ": region " << id;
    const RegionMesh& other = a.regions().at(id);
    ASSERT_EQ(testing::trianglesOverIds(other), testing::trianglesOverIds(mesh)) << when << ": region " << id;
    std::map<uint64_t, Vec3> positions;
    for (size_t v = 0; v < mesh.positions.size(); ++v) positions[mesh.vertexIds[v]] = mesh.positions[v];
    for (size_t v = 0; v < other.positions.size(); ++v) {
      const Vec3& p = positions.at(other.vertexIds[v]);
      ASSERT_EQ(std::memcmp(&p, &other.positions[v], sizeof(Vec3)), 0)
          << when << ": region " << id << " vertex " << VertexId::fromPacked(other.vertexIds[v]).toString();
    }
  }
}

wire::ClientMessage crease(uint64_t doc, EdgeId e, float sharpness) {
  wire::ClientMessage m;
  m.mutable_set_edge_sharpness()->set_document_id(doc);
  m.mutable_set_edge_sharpness()->set_edge_id(e.packed());
  m.mutable_set_edge_sharpness()->set_sharpness(sharpness);
  return m;
}

TEST(ServerCatmark, AQuadModelIsServedAsACatmullClarkDocument) {
  const std::string dir = testing::makeTempDir("tessera-catmark");
  auto server = ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());

  // Refusals name what and why.
  auto loop = (*admin)->call(createQuadCube(wire::SUBDIVISION_SCHEME_LOOP), 30);
  ASSERT_TRUE(loop.isOk() && loop->has_reject()) << loop->DebugString();
  EXPECT_NE(loop->reject().message().find("cube_quads.obj"), std::string::npos) << loop->reject().message();
  EXPECT_NE(loop->reject().message().find("only triangles"), std::string::npos) << loop->reject().message();
  auto triangulated = (*admin)->call(createQuadCube(wire::SUBDIVISION_SCHEME_CATMULL_CLARK, true), 30);
  ASSERT_TRUE(triangulated.isOk() && triangulated->has_reject()) << triangulated->DebugString();
  EXPECT_NE(
      triangulated->reject().message().find("triangulate is not available for a catmull-clark document"),
      std::string::npos)
      << triangulated->reject().message();
  // Quads and no scheme: Catmull-Clark, said in the Ack.
  auto created = (*admin)->call(createQuadCube(wire::SUBDIVISION_SCHEME_UNSPECIFIED), 30);
  ASSERT_TRUE(created.isOk() && created->has_ack()) << created->DebugString();
  EXPECT_EQ(created->ack().scheme(), wire::SUBDIVISION_SCHEME_CATMULL_CLARK);
  const uint64_t doc = created->ack().document_id();
  // Triangulated and no scheme: Loop, as before.
  auto asLoop = (*admin)->call(createQuadCube(wire::SUBDIVISION_SCHEME_UNSPECIFIED, true), 30);
  ASSERT_TRUE(asLoop.isOk() && asLoop->has_ack()) << asLoop->DebugString();
  EXPECT_EQ(asLoop->ack().scheme(), wire::SUBDIVISION_SCHEME_LOOP);

  ASSERT_TRUE(
      (*admin)->call(testing::grant(doc, wire::ROLE_EDITOR, "editor-token-0123456789"), 10)->has_ack());
  ASSERT_TRUE(
      (*admin)->call(testing::grant(doc, wire::ROLE_VIEWER, "viewer-token-0123456789"), 10)->has_ack());
  auto viewer = Session::connect(server->session("viewer", "viewer-token-0123456789"));
  auto editor = Session::connect(server->session("editor", "editor-token-0123456789"));
  ASSERT_TRUE(viewer.isOk() && editor.isOk());
  ASSERT_TRUE((*viewer)->call(testing::openDocument(doc), 10)->has_ack());
  ASSERT_TRUE((*editor)->call(testing::openDocument(doc), 10)->has_ack());

  ASSERT_TRUE((*viewer)->call(testing::subscribe(doc, 1, kMaxLevel), 30)->has_ack());
  DocumentView seen(doc);
  readUntil(**viewer, seen, 1);

  // The same document locally: the reference for every step.
  auto polygons = schemes::importPolygonMesh(quadCubePath(), "");
  ASSERT_TRUE(polygons.isOk());
  auto local = Document::create(polygons->topology, polygons->points,
                                {.maxLevel = kMaxLevel, .scheme = DocumentScheme::kCatmullClark});
  ASSERT_TRUE(local.isOk()) << local.status().toString();
  // 13 bits over five times the unit cube's extent: 6e-4 per step.
  constexpr double kQuantized = 1e-3;
  auto expectLocal = [&](const std::string& when) {
    auto t = Tessellation::build(*local, kProfile);
    ASSERT_TRUE(t.isOk()) << t.status().toString();
    expectStreamedIsLocal(seen, *t, kQuantized, when);
  };
  expectLocal("created");

  // A drag: v1:7's limit goes to the target.
  const VertexId corner(1, 7);
  const Vec3 target(1.1, 1.05, 1.2);
  auto moved =
      (*editor)->call(testing::moveVertex(doc, corner.packed(), target[0], target[1], target[2]), 10);
  ASSERT_TRUE(moved.isOk() && moved->has_ack()) << moved->DebugString();
  ASSERT_TRUE(local->moveToLimit(std::span(&corner, 1), target).isOk());
  readUntil(**viewer, seen, 2);
  expectLocal("a drag at level 1");
  double landed = 1e9;
  for (const auto& [id, region] : seen.regions()) {
    for (size_t v = 0; v < region.positions.size(); ++v) {
      // Shown under its birth id: v1:7 is the child of base vertex 7.
      if (region.vertexIds[v] == VertexId(0, 7).packed())
        landed = std::min(landed, (region.positions[v] - target).norm());
    }
  }
  EXPECT_LE(landed, kQuantized) << corner.toString() << "'s streamed limit is not at its target";

  // An offset, a crease, and a batch of two offsets.
  const VertexId fine(2, 30);
  ASSERT_TRUE((*editor)
                  ->call(testing::moveVertex(doc, fine.packed(), 0, 0, 0.05, wire::MOVE_MODE_OFFSET), 10)
                  ->has_ack());
  ASSERT_TRUE(local->moveBy(std::span(&fine, 1), Vec3(0, 0, 0.05)).isOk());
  auto creased = (*editor)->call(crease(doc, EdgeId(0, 0), 2.0f), 10);
  ASSERT_TRUE(creased.isOk() && creased->has_ack()) << creased->DebugString();
  ASSERT_TRUE(local->setEdgeSharpness(EdgeId(0, 0), 2.0f).isOk());
  wire::ClientMessage batch;
  batch.mutable_edit_batch()->set_document_id(doc);
  for (const VertexId v : {VertexId(0, 2), VertexId(3, 100)}) {
    *batch.mutable_edit_batch()->add_commands()->mutable_move_vertex() =
        testing::moveVertex(doc, v.packed(), 0.02, -0.03, 0.04, wire::MOVE_MODE_OFFSET).move_vertex();
    ASSERT_TRUE(local->moveBy(std::span(&v, 1), Vec3(0.02, -0.03, 0.04)).isOk());
  }
  auto batched = (*editor)->call(batch, 10);
  ASSERT_TRUE(batched.isOk() && batched->has_ack()) << batched->DebugString();
  ASSERT_EQ(batched->ack().version(), 5u);
  readUntil(**viewer, seen, 5);
  expectLocal("an offset, a crease and a batch");

  // Undo the crease.
  wire::ClientMessage undo;
  undo.mutable_undo()->set_document_id(doc);
  undo.mutable_undo()->set_edit_id(creased->ack().edit_id());
  ASSERT_TRUE((*editor)->call(undo, 10)->has_ack());
  ASSERT_TRUE(local->undo(local->edits()[2].id).isOk());
  readUntil(**viewer, seen, 6);
  expectLocal("an undo");
  const uint64_t shown = seen.surfaceHash();

  // A late joiner sees what the first viewer holds.
  auto late = Session::connect(server->session("late", "viewer-token-0123456789"));
  ASSERT_TRUE(late.isOk());
  ASSERT_TRUE((*late)->call(testing::openDocument(doc), 10)->has_ack());
  ASSERT_TRUE((*late)->call(testing::subscribe(doc, 1, kMaxLevel), 30)->has_ack());
  DocumentView joined(doc);
  readUntil(**late, joined, 6);
  EXPECT_EQ(joined.surfaceHash(), shown);
  expectSameDecodedRegions(joined, seen, "late joiner");

  // The journal brings it back after a restart, bit for bit.
  EXPECT_EQ(server->stop(), 0);
  auto again = ServerProcess::start(dir + "/data");
  ASSERT_TRUE(again.isOk()) << again.status().message();
  auto back = Session::connect(again->session("back", "viewer-token-0123456789"));
  ASSERT_TRUE(back.isOk());
  ASSERT_TRUE((*back)->call(testing::openDocument(doc), 10)->has_ack());
  ASSERT_TRUE((*back)->call(testing::subscribe(doc, 1, kMaxLevel), 30)->has_ack());
  DocumentView restored(doc);
  readUntil(**back, restored, 6);
  EXPECT_EQ(restored.surfaceHash(), shown);
  expectSameDecodedRegions(restored, seen, "after a restart");
  EXPECT_EQ(again->stop(), 0);
}

}  // namespace
}  // namespace tessera
