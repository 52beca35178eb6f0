// Interpolating vertices (docs/INTERPOLATION.md) through the service: SetInterpolation on the real
// tessera-server (127.0.0.1, real store), a viewer whose streamed surface
// then passes through the vertex's control point, the command relayed to
// with_commands subscribers, refusals that name the vertex, undo, and the
// tag surviving a restart (journal replay).
#include <gtest/gtest.h>

#include <cstdio>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "core/document/document.h"
#include "core/hierarchy/ids.h"
#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"
#include "core/loop/ghost_ring.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::ServerProcess;

constexpr int kMaxLevel = 4;

// The creased cube as the server holds it after CreateDocument, evaluated
// locally: the reference for control points.
Document localCube() {
  auto mesh = importMesh(testing::sourceTestDataPath("cube.obj"));
  EXPECT_TRUE(mesh.isOk());
  EXPECT_TRUE(applyTagFile(testing::sourceTestDataPath("cube.tags"), *mesh).isOk());
  auto doc = Document::create(*mesh, {.maxLevel = kMaxLevel});
  EXPECT_TRUE(doc.isOk());
  return std::move(*doc);
}

wire::ClientMessage setInterpolation(uint64_t doc, VertexId v, bool on, double tension) {
  wire::ClientMessage m;
  auto* t = m.mutable_set_interpolation();
  t->set_document_id(doc);
  t->set_vertex_id(v.packed());
  t->set_interpolating(on);
  t->set_tension(tension);
  return m;
}

// Reads until `view` reaches `version`; AppliedCommands go to `applied`.
void readUntil(Session& s, DocumentView& view, uint64_t version,
               std::vector<wire::AppliedCommand>* applied = nullptr) {
  for (int i = 0; i < 400 && (!view.ready() || view.version() < version); ++i) {
    auto m = s.receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    if (m->has_applied_command() && applied != nullptr) applied->push_back(m->applied_command());
    Status ok = view.apply(*m);
    ASSERT_TRUE(ok.isOk()) << ok.message();
  }
  ASSERT_TRUE(view.ready());
  ASSERT_EQ(view.version(), version);
}

// The farthest any streamed limit of the vertex (its descendants keep its
// index) lies from `point`, and how many there are.
std::pair<double, int> streamedDistance(const DocumentView& view, VertexId v, const Vec3& point) {
  double worst = 0;
  int count = 0;
  for (const auto& [id, region] : view.regions()) {
    for (size_t i = 0; i < region.positions.size(); ++i) {
      const VertexId shown = VertexId::fromPacked(region.vertexIds[i]);
      if (shown.level() < v.level() || shown.index() != v.index()) continue;
      worst = std::max(worst, (region.positions[i] - point).norm());
      ++count;
    }
  }
  return {worst, count};
}

TEST(ServerInterpolation, TheStreamedSurfacePassesThroughTheTaggedVertex) {
  Document local = localCube();
  // A smooth level-1 vertex of the creased cube, and its control point.
  auto eval = local.evaluate(1);
  ASSERT_TRUE(eval.isOk());
  VertexId v;
  for (Index i = static_cast<Index>(local.counts().vertices(0)); i < (*eval)->levels[1].numVertices; ++i) {
    if (ghostRuleOf((*eval)->levels[1], i) == GhostRule::kInterior) {
      v = VertexId(1, static_cast<uint64_t>(i));
      break;
    }
  }
  // Lifted off its face first, so that plain Loop does not pass through it.
  const Vec3 lift(0.15, -0.1, 0.2);
  ASSERT_TRUE(local.moveBy(std::span(&v, 1), lift).isOk());
  const Vec3 control = (*local.evaluate(1))->points[1][v.index()];

  const std::string dir = testing::makeTempDir("tessera-interp");
  auto server = ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());
  auto created = (*admin)->call(
      testing::createDocument("cube", testing::fileBytes(testing::sourceTestDataPath("cube.obj")),
                              testing::fileBytes(testing::sourceTestDataPath("cube.tags")), kMaxLevel),
      30);
  ASSERT_TRUE(created.isOk() && created->has_ack()) << created->DebugString();
  const uint64_t doc = created->ack().document_id();
  ASSERT_TRUE(
      (*admin)->call(testing::grant(doc, wire::ROLE_EDITOR, "editor-token-0123456789"), 10)->has_ack());
  ASSERT_TRUE(
      (*admin)->call(testing::grant(doc, wire::ROLE_VIEWER, "viewer-token-0123456789"), 10)->has_ack());

  auto viewer = Session::connect(server->session("viewer", "viewer-token-0123456789"));
  auto editor = Session::connect(server->session("editor", "editor-token-0123456789"));
  ASSERT_TRUE(viewer.isOk() && editor.isOk());
  ASSERT_TRUE((*viewer)->call(testing::openDocument(doc), 10)->has_ack());
  wire::ClientMessage sub = testing::subscribe(doc, 1, kMaxLevel);
  sub.mutable_subscribe()->set_with_commands(true);
  ASSERT_TRUE((*viewer)->call(sub, 30)->has_ack());
  ASSERT_TRUE((*editor)->call(testing::openDocument(doc), 10)->has_ack());
  auto lifted = (*editor)->call(
      testing::moveVertex(doc, v.packed(), lift[0], lift[1], lift[2], wire::MOVE_MODE_OFFSET), 10);
  ASSERT_TRUE(lifted.isOk() && lifted->has_ack()) << lifted->DebugString();
  DocumentView seen(doc);
  readUntil(**viewer, seen, 2);
  const auto [plainDistance, plainCount] = streamedDistance(seen, v, control);
  ASSERT_GT(plainCount, 0) << v.toString() << " is not displayed";
  EXPECT_GT(plainDistance, 1e-2) << "plain Loop passes near the control point already";

  // Refusals name the vertex and why; nothing changes.
  for (const auto& [message, why] : std::vector<std::pair<wire::ClientMessage, std::string>>{
           {setInterpolation(doc, v, true, -2), v.toString() + ": tension must be in [0.001, 1000]"},
           {setInterpolation(doc, VertexId(kMaxLevel, 3), true, 1),
            "must lie above the document's deepest level 4"},
           {setInterpolation(doc, VertexId(1, 6), true, 1),
            "v1:6 cannot interpolate: it is a corner or cusp"},
           {setInterpolation(doc, VertexId(1, 0), true, 1),
            "v1:0 cannot interpolate: a semi-sharp edge meets it"}}) {
    auto refused = (*editor)->call(message, 10);
    ASSERT_TRUE(refused.isOk() && refused->has_reject()) << refused->DebugString();
    EXPECT_NE(refused->reject().message().find(why), std::string::npos) << refused->reject().message();
  }

  auto acked = (*editor)->call(setInterpolation(doc, v, true, 2.0), 10);
  ASSERT_TRUE(acked.isOk() && acked->has_ack()) << acked->DebugString();
  ASSERT_EQ(acked->ack().version(), 3u);
  std::vector<wire::AppliedCommand> applied;
  readUntil(**viewer, seen, 3, &applied);
  // The command follows the delta of its version.
  for (int i = 0; i < 100 && (applied.empty() || !applied.back().has_set_interpolation()); ++i) {
    auto m = (*viewer)->receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    if (m->has_applied_command()) applied.push_back(m->applied_command());
  }
  const auto [taggedDistance, taggedCount] = streamedDistance(seen, v, control);
  ASSERT_GT(taggedCount, 0);
  // The stream quantizes positions (13 bits over the cube's ~2.6 units:
  // 3.2e-4 per step); the surface now passes through the control point.
  EXPECT_LE(taggedDistance, 1e-3) << "plain " << plainDistance;
  std::printf(
      "streamed limit of %s from its control point: %.3g plain, %.3g interpolating (%d and %d vertices)\n",
      v.toString().c_str(), plainDistance, taggedDistance, plainCount, taggedCount);
  ASSERT_FALSE(applied.empty());
  EXPECT_TRUE(applied.back().has_set_interpolation());
  EXPECT_EQ(applied.back().set_interpolation().vertex_id(), v.packed());
  const uint64_t tagged = seen.surfaceHash();

  // A finer move in its ghost ring is refused; undo brings plain Loop back.
  wire::ClientMessage nearMove =
      testing::moveVertex(doc, VertexId(2, v.index()).packed(), 0, 0, 0.1, wire::MOVE_MODE_OFFSET);
  auto refused = (*editor)->call(nearMove, 10);
  ASSERT_TRUE(refused.isOk() && refused->has_reject());
  EXPECT_NE(refused->reject().message().find("conflicts with interpolating vertex " + v.toString()),
            std::string::npos)
      << refused->reject().message();
  wire::ClientMessage undo;
  undo.mutable_undo()->set_document_id(doc);
  undo.mutable_undo()->set_edit_id(acked->ack().edit_id());
  ASSERT_TRUE((*editor)->call(undo, 10)->has_ack());
  readUntil(**viewer, seen, 4);
  EXPECT_NEAR(streamedDistance(seen, v, control).first, plainDistance, 1e-3);
  wire::ClientMessage redo;
  redo.mutable_redo()->set_document_id(doc);
  redo.mutable_redo()->set_edit_id(acked->ack().edit_id());
  ASSERT_TRUE((*editor)->call(redo, 10)->has_ack());
  readUntil(**viewer, seen, 5);
  EXPECT_EQ(seen.surfaceHash(), tagged);

  // The journal brings it back after a restart.
  EXPECT_EQ(server->stop(), 0);
  auto again = ServerProcess::start(dir + "/data");
  ASSERT_TRUE(again.isOk()) << again.status().message();
  auto back = Session::connect(again->session("back", "viewer-token-0123456789"));
  ASSERT_TRUE(back.isOk());
  ASSERT_TRUE((*back)->call(testing::openDocument(doc), 10)->has_ack());
  ASSERT_TRUE((*back)->call(testing::subscribe(doc, 1, kMaxLevel), 30)->has_ack());
  DocumentView restored(doc);
  readUntil(**back, restored, 5);
  EXPECT_EQ(restored.surfaceHash(), tagged);
  EXPECT_LE(streamedDistance(restored, v, control).first, 1e-3);
  EXPECT_EQ(again->stop(), 0);
}

}  // namespace
}  // namespace tessera
