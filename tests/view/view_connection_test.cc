// tessera-view's Connection against the real server, without a window: the
// published regions follow edits, undo and redo of its own edits, the
// edit-to-delta latency is measured, and presence shows collaborators'
// selections.
#include <gtest/gtest.h>

#include <limits>
#include <optional>

#include "client/view/connection.h"
#include "core/document/document.h"
#include "core/hierarchy/ids.h"
#include "core/hierarchy/incidence.h"
#include "core/io/mesh_import.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "protocol/commands.h"
#include "support/test_meshes.h"
#include "view/cube_document.h"
#include "view/wait_for.h"

namespace tessera::view {
namespace {

using testing::viewOptionsFor;
using testing::waitFor;

// The positions of every published region, in region order.
std::vector<double> positions(const RegionMap& regions) {
  std::vector<double> out;
  for (const auto& [id, mesh] : regions)
    for (const Vec3& p : mesh->positions) out.insert(out.end(), {p[0], p[1], p[2]});
  return out;
}

TEST(ViewConnection, FollowsItsOwnEditsThroughUndoAndRedoAndShowsSelections) {
  const std::string dir = testing::makeTempDir("tessera-view-connection");
  auto server = testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto created = testing::createCube(*server, true, 5);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  const uint64_t doc = *created;

  ViewOptions options = viewOptionsFor(*server, doc, 2, 3);
  options.name = "viewer-under-test";
  auto connection = Connection::open(options);
  ASSERT_TRUE(connection.isOk()) << connection.status().message();
  Connection& c = **connection;
  ASSERT_TRUE(waitFor([&] { return c.stats().ready; }));
  EXPECT_EQ(c.stats().version, 1u);
  const std::vector<double> before = positions(c.regions());
  ASSERT_FALSE(before.empty());

  c.moveVertex(VertexId(2, 0).packed(), Vec3(0.1, 0.2, 1.4));
  ASSERT_TRUE(waitFor([&] { return c.stats().version == 2 && c.stats().editsPending == 0; }));
  const std::vector<double> moved = positions(c.regions());
  EXPECT_NE(moved, before);
  EXPECT_EQ(c.stats().latencySamples, 1u);
  EXPECT_GE(c.stats().lastLatencyMs, 0);

  c.undo();
  ASSERT_TRUE(waitFor([&] { return c.stats().version == 3 && c.stats().editsPending == 0; }));
  EXPECT_EQ(positions(c.regions()), before);
  c.redo();
  ASSERT_TRUE(waitFor([&] { return c.stats().version == 4 && c.stats().editsPending == 0; }));
  EXPECT_EQ(positions(c.regions()), moved);
  c.undo();
  EXPECT_FALSE(c.undo());  // nothing more of its own to undo: ignored
  ASSERT_TRUE(waitFor([&] { return c.stats().version == 5 && c.stats().editsPending == 0; }));
  EXPECT_EQ(c.stats().editsSent, 4u);
  EXPECT_EQ(c.stats().editsRejected, 0u);
  EXPECT_EQ(c.stats().latencySamples, 4u);

  // Another participant selects a vertex; so does the viewer.
  auto other = client::Session::connect(server->session("alice", server->adminToken()));
  ASSERT_TRUE(other.isOk());
  ASSERT_TRUE((*other)->call(testing::openDocument(doc), 10)->has_ack());
  wire::ClientMessage select;
  select.mutable_select()->set_document_id(doc);
  select.mutable_select()->mutable_selection()->add_vertex_ids(VertexId(0, 6).packed());
  ASSERT_TRUE((*other)->send(select).isOk());
  c.select({VertexId(0, 0).packed()});
  ASSERT_TRUE(waitFor([&] {
    bool alice = false, self = false;
    for (const Collaborator& p : c.collaborators()) {
      alice |= p.name == "alice" && p.selectedVertices == std::vector<uint64_t>{VertexId(0, 6).packed()};
      self |= p.self && p.name == "viewer-under-test" && p.selectedVertices == std::vector<uint64_t>{0};
    }
    return alice && self;
  }));
  EXPECT_TRUE(c.stats().connected);
  EXPECT_EQ(c.stats().gaps, 0u);

  // A coarser LOD profile: unsubscribe, subscribe, a new snapshot.
  auto triangles = [](const RegionMap& regions) {
    size_t n = 0;
    for (const auto& [id, mesh] : regions) n += mesh->triangles.size();
    return n;
  };
  const size_t fine = triangles(c.regions());
  EXPECT_EQ(c.stats().snapshots, 1u);
  c.changeProfile(1, 1, 15);
  ASSERT_TRUE(waitFor([&] { return c.stats().snapshots == 2 && c.stats().ready; })) << c.stats().lastError;
  EXPECT_LT(triangles(c.regions()), fine);
  EXPECT_EQ(c.stats().version, 5u);

  // The K key: the picked vertex becomes a corner.
  c.setVertexType(VertexId(0, 6).packed(), wire::VERTEX_TYPE_CORNER);
  ASSERT_TRUE(waitFor([&] { return c.stats().version == 6 && c.stats().editsPending == 0; }))
      << c.stats().lastError;
  EXPECT_EQ(c.stats().editsRejected, 0u);
}

TEST(ViewConnection, ReconnectsAndResubscribesAfterTheServerRestarts) {
  const std::string dir = testing::makeTempDir("tessera-view-reconnect");
  auto server = testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto created = testing::createCube(*server, false, 4);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  const uint64_t doc = *created;
  const ViewOptions options = viewOptionsFor(*server, doc, 1, 1);
  auto connection = Connection::open(options);
  ASSERT_TRUE(connection.isOk()) << connection.status().message();
  Connection& c = **connection;
  ASSERT_TRUE(waitFor([&] { return c.stats().ready; }));
  const uint64_t firstSession = c.stats().sessionId;

  // Stop the server, then start it again on the same port and data.
  const uint16_t port = server->port();
  EXPECT_EQ(server->stop(), 0);
  ASSERT_TRUE(waitFor([&] { return !c.stats().connected; }));
  auto again = testing::ServerProcess::start(dir + "/data", {"--port", std::to_string(port)});
  ASSERT_TRUE(again.isOk()) << again.status().message();
  ASSERT_EQ(again->port(), port);
  ASSERT_TRUE(waitFor([&] { return c.stats().connected && c.stats().ready; })) << c.stats().lastError;
  EXPECT_EQ(c.stats().reconnects, 1u);
  EXPECT_NE(c.stats().sessionId, firstSession);
  EXPECT_FALSE(c.regions().empty());
  // Edits work on the new connection.
  c.moveVertex(VertexId(1, 0).packed(), Vec3(-0.2, -0.2, -0.2));
  ASSERT_TRUE(waitFor([&] { return c.stats().version == 2 && c.stats().editsPending == 0; }))
      << c.stats().lastError;
  EXPECT_EQ(c.stats().editsRejected, 0u);
}

// A server with the cube (with its tags), and a Connection keeping the
// surface hash, at a uniform level 2 tessellation.
struct CubeFixture {
  std::optional<testing::ServerProcess> server;
  std::unique_ptr<Connection> connection;
  uint64_t doc = 0;

  void start(const std::string& name) {
    auto started = testing::ServerProcess::start(testing::makeTempDir(name) + "/data");
    ASSERT_TRUE(started.isOk()) << started.status().message();
    server.emplace(std::move(*started));
    auto created = testing::createCube(*server, true, 4);
    ASSERT_TRUE(created.isOk()) << created.status().message();
    doc = *created;
    ViewOptions options = viewOptionsFor(*server, doc, 2, 2);
    options.hashSurfaces = true;
    auto opened = Connection::open(options);
    ASSERT_TRUE(opened.isOk()) << opened.status().message();
    connection = std::move(*opened);
    ASSERT_TRUE(waitFor([&] { return connection->stats().ready; }));
    ASSERT_NE(connection->stats().surfaceHash, 0u);
  }
  // A drag as the mouse makes it: `moves` MoveVertex edits of one vertex,
  // the i-th to i * `step`, in one undo step. With `open`, the step is left
  // open (the button still down).
  UndoHistory::StepId drag(VertexId vertex, int moves, const Vec3& step, bool open = false) {
    const UndoHistory::StepId id = connection->openStep();
    for (int i = 1; i <= moves; ++i) connection->moveVertex(vertex.packed(), step * i, id);
    if (!open) connection->closeStep(id);
    return id;
  }
  // Waits until the document is at `version` with nothing pending.
  bool reaches(uint64_t version) {
    return waitFor(
        [&] { return connection->stats().version == version && connection->stats().editsPending == 0; });
  }
};

TEST(ViewConnection, UndoAndRedoStepOverAWholeDrag) {
  CubeFixture f;
  ASSERT_NO_FATAL_FAILURE(f.start("tessera-view-drag-undo"));
  Connection& c = *f.connection;
  const uint64_t before = c.stats().surfaceHash;

  // A drag: five moves of one vertex in one step, as the mouse sends them.
  const UndoHistory::StepId drag = f.drag(VertexId(2, 0), 5, Vec3(-0.05, -0.05, -0.02), true);
  EXPECT_FALSE(c.undo()) << "undo while the drag is still being made";
  c.closeStep(drag);
  ASSERT_TRUE(f.reaches(6)) << c.stats().lastError;
  const uint64_t dragged = c.stats().surfaceHash;
  EXPECT_NE(dragged, before);

  // One undo takes back all five edits, newest first; one redo replays them.
  ASSERT_TRUE(c.undo()) << c.stats().lastError;
  ASSERT_TRUE(f.reaches(11)) << c.stats().lastError;
  EXPECT_EQ(c.stats().surfaceHash, before);
  EXPECT_FALSE(c.undo()) << "the drag was the only step";
  ASSERT_TRUE(c.redo()) << c.stats().lastError;
  ASSERT_TRUE(f.reaches(16)) << c.stats().lastError;
  EXPECT_EQ(c.stats().surfaceHash, dragged);

  // A single edit after the drag is a step of its own.
  c.setVertexType(VertexId(2, 0).packed(), wire::VERTEX_TYPE_CORNER);
  ASSERT_TRUE(f.reaches(17)) << c.stats().lastError;
  ASSERT_TRUE(c.undo());
  ASSERT_TRUE(f.reaches(18)) << c.stats().lastError;
  EXPECT_EQ(c.stats().surfaceHash, dragged);
  ASSERT_TRUE(c.undo());
  ASSERT_TRUE(f.reaches(23)) << c.stats().lastError;
  EXPECT_EQ(c.stats().surfaceHash, before);
  EXPECT_EQ(c.stats().editsRejected, 0u);
}

// A long drag (30 edits a second for over 8 s) has more edits than the
// server's burst of 200 commands: its undo is paced, and none is refused.
TEST(ViewConnection, UndoOfALongDragStaysUnderTheRateLimit) {
  CubeFixture f;
  ASSERT_NO_FATAL_FAILURE(f.start("tessera-view-long-drag"));
  Connection& c = *f.connection;
  const uint64_t before = c.stats().surfaceHash;
  const int moves = 250;
  f.drag(VertexId(2, 3), moves, Vec3(0.001, 0.0, 0.0));
  ASSERT_TRUE(f.reaches(1 + moves)) << c.stats().lastError;
  ASSERT_TRUE(c.undo()) << c.stats().lastError;
  ASSERT_TRUE(f.reaches(1 + 2 * moves)) << c.stats().lastError;
  EXPECT_EQ(c.stats().surfaceHash, before);
  EXPECT_EQ(c.stats().editsRejected, 0u) << c.stats().lastError;
}

TEST(ViewConnection, SetsAnEdgeSharpByItsEndsAndUndoesIt) {
  CubeFixture f;
  ASSERT_NO_FATAL_FAILURE(f.start("tessera-view-edge"));
  Connection& c = *f.connection;
  const uint64_t before = c.stats().surfaceHash;

  // A level-1 half of the bottom rim, smooth from level 1 on (its tag is
  // 1), its ends found by the core's arithmetic from the base mesh (the
  // viewer itself only has vertex ids).
  auto mesh = importMesh(testing::sourceTestDataPath("cube.obj"));
  ASSERT_TRUE(mesh.isOk()) << mesh.status().message();
  auto local = Document::create(*mesh, {.loop = {}, .maxLevel = 4});
  ASSERT_TRUE(local.isOk());
  auto rim = local->edgeBetween(VertexId(0, 0), VertexId(0, 1));
  ASSERT_TRUE(rim.isOk()) << rim.status().message();
  const EdgeId half(1, 2 * rim->index());
  const auto ends = edgeEnds(local->hierarchy().level(0).mesh, local->counts(), half);

  c.setEdgeSharpness(ends[1].packed(), ends[0].packed(), std::numeric_limits<float>::infinity());
  ASSERT_TRUE(f.reaches(2)) << c.stats().lastError;
  const uint64_t sharp = c.stats().surfaceHash;
  EXPECT_NE(sharp, before);
  ASSERT_TRUE(c.undo());
  ASSERT_TRUE(f.reaches(3)) << c.stats().lastError;
  EXPECT_EQ(c.stats().surfaceHash, before);
  ASSERT_TRUE(c.redo());
  ASSERT_TRUE(f.reaches(4)) << c.stats().lastError;
  EXPECT_EQ(c.stats().surfaceHash, sharp);
  EXPECT_EQ(c.stats().editsRejected, 0u);

  // Refused, naming both ids: not joined, and on different levels.
  const VertexId far(0, 0), opposite(0, 6);  // opposite corners of the cube
  c.setEdgeSharpness(far.packed(), opposite.packed(), 10.0f);
  ASSERT_TRUE(waitFor([&] { return c.stats().editsRejected == 1 && c.stats().editsPending == 0; }));
  EXPECT_NE(c.stats().lastError.find("REJECT_REASON_INVALID_ARGUMENT"), std::string::npos)
      << c.stats().lastError;
  EXPECT_NE(c.stats().lastError.find("v0:0 and v0:6 are not joined"), std::string::npos)
      << c.stats().lastError;
  c.setEdgeSharpness(ends[0].packed(), VertexId(2, ends[1].index()).packed(), 10.0f);
  ASSERT_TRUE(waitFor([&] { return c.stats().editsRejected == 2 && c.stats().editsPending == 0; }));
  EXPECT_NE(c.stats().lastError.find(ends[0].toString() + " and v2:" + std::to_string(ends[1].index()) +
                                     " lie on different levels"),
            std::string::npos)
      << c.stats().lastError;
  EXPECT_EQ(c.stats().version, 4u) << "a refused edit makes no version";

  // On the wire: edge_id must be all ones beside the ends, and the ends two.
  auto raw = client::Session::connect(f.server->session("raw", f.server->adminToken()));
  ASSERT_TRUE(raw.isOk()) << raw.status().message();
  ASSERT_TRUE((*raw)->call(testing::openDocument(f.doc), 10)->has_ack());
  for (int ids : {1, 2, 3}) {
    wire::ClientMessage m;
    auto* e = m.mutable_set_edge_sharpness();
    e->set_document_id(f.doc);
    e->set_edge_id(ids == 2 ? 0 : kEdgeIdNamedByEnds);  // 0 would name e0:0 on an older server
    for (int i = 0; i < ids; ++i) e->add_end_vertex_ids(ends[i % 2].packed());
    e->set_sharpness(10.0f);
    auto reply = (*raw)->call(m, 10);
    ASSERT_TRUE(reply.isOk() && reply->has_reject()) << ids << " ids";
    EXPECT_EQ(reply->reject().reason(), wire::REJECT_REASON_INVALID_ARGUMENT);
    EXPECT_NE(reply->reject().message().find("end_vertex_ids needs exactly two ids and edge_id all ones"),
              std::string::npos)
        << reply->reject().message();
  }
  // The refused edits are no undo steps: undo takes back the sharp edge.
  ASSERT_TRUE(c.undo());
  ASSERT_TRUE(f.reaches(5)) << c.stats().lastError;
  EXPECT_EQ(c.stats().surfaceHash, before);
}

}  // namespace
}  // namespace tessera::view
