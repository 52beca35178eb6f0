// tessera-server end to end (docs/PROTOCOL.md): the real binary on
// 127.0.0.1, a real SQLite data directory, real clients.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <fstream>
#include <map>
#include <set>
#include <thread>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "core/hierarchy/ids.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "protocol/framing.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::ServerProcess;

// Reads messages until `view` has a full snapshot (or the deadline).
void waitForSnapshot(Session& s, DocumentView& view) {
  for (int i = 0; i < 200 && !view.ready(); ++i) {
    auto m = s.receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    ASSERT_TRUE(view.apply(*m).isOk());
  }
  ASSERT_TRUE(view.ready());
}

// Reads until the view reaches `version`.
void waitForVersion(Session& s, DocumentView& view, uint64_t version) {
  for (int i = 0; i < 200 && view.version() < version; ++i) {
    auto m = s.receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    Status applied = view.apply(*m);
    ASSERT_TRUE(applied.isOk()) << applied.message();
  }
  ASSERT_EQ(view.version(), version);
}

struct Fixture {
  std::string dir;
  std::optional<ServerProcess> server;
  uint64_t doc = 0;
};

// A server with the creased cube as document, and viewer/editor tokens.
void startWithCube(Fixture& f, const std::string& name, const std::vector<std::string>& serverArgs = {}) {
  f.dir = testing::makeTempDir(name);
  auto server = ServerProcess::start(f.dir + "/data", serverArgs);
  ASSERT_TRUE(server.isOk()) << server.status().message();
  f.server.emplace(std::move(*server));
  auto admin = Session::connect(f.server->session("admin", f.server->adminToken()));
  ASSERT_TRUE(admin.isOk()) << admin.status().message();
  EXPECT_EQ((*admin)->role(), wire::ROLE_ADMIN);
  auto created = (*admin)->call(
      testing::createDocument("cube", testing::fileBytes(testing::sourceTestDataPath("cube.obj")),
                              testing::fileBytes(testing::sourceTestDataPath("cube.tags")), 5),
      30);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  ASSERT_TRUE(created->has_ack()) << created->DebugString();
  f.doc = created->ack().document_id();
  for (auto [role, token] : {std::pair{wire::ROLE_VIEWER, "viewer-token-0123456789"},
                             std::pair{wire::ROLE_EDITOR, "editor-token-0123456789"}}) {
    auto granted = (*admin)->call(testing::grant(f.doc, role, token), 10);
    ASSERT_TRUE(granted.isOk() && granted->has_ack())
        << (granted.isOk() ? granted->DebugString() : granted.status().message());
  }
}

TEST(Server, EditsStreamToEveryViewerAndLateJoinersCatchUp) {
  Fixture f;
  startWithCube(f, "tessera-server-e2e");
  if (::testing::Test::HasFatalFailure()) return;
  auto viewer = Session::connect(f.server->session("viewer", "viewer-token-0123456789"));
  auto editor = Session::connect(f.server->session("editor", "editor-token-0123456789"));
  ASSERT_TRUE(viewer.isOk() && editor.isOk());
  for (Session* s : {viewer->get(), editor->get()}) {
    auto opened = s->call(testing::openDocument(f.doc), 10);
    ASSERT_TRUE(opened.isOk() && opened->has_ack())
        << (opened.isOk() ? opened->DebugString() : opened.status().message());
    auto subscribed = s->call(testing::subscribe(f.doc, 1, 4), 30);
    ASSERT_TRUE(subscribed.isOk() && subscribed->has_ack()) << subscribed->DebugString();
  }
  DocumentView seen(f.doc), edited(f.doc);
  waitForSnapshot(**viewer, seen);
  waitForSnapshot(**editor, edited);
  EXPECT_EQ(seen.version(), 1u);
  EXPECT_GT(seen.numTriangles(), 12 * 4);
  const uint64_t before = seen.surfaceHash();

  // A direct-manipulation edit: acked after it is durable, streamed to both.
  auto acked = (*editor)->call(testing::moveVertex(f.doc, VertexId(2, 0).packed(), 0.1, 0.2, 1.4), 10);
  ASSERT_TRUE(acked.isOk() && acked->has_ack()) << acked->DebugString();
  EXPECT_EQ(acked->ack().version(), 2u);
  EXPECT_EQ(acked->ack().edit_id(), 1u);
  waitForVersion(**viewer, seen, 2);
  waitForVersion(**editor, edited, 2);
  EXPECT_NE(seen.surfaceHash(), before);
  EXPECT_EQ(seen.surfaceHash(), edited.surfaceHash());
  EXPECT_EQ(seen.gaps(), 0u);

  // A late joiner's snapshot equals the state the deltas built.
  auto late = Session::connect(f.server->session("late", "viewer-token-0123456789"));
  ASSERT_TRUE(late.isOk());
  ASSERT_TRUE((*late)->call(testing::openDocument(f.doc), 10)->has_ack());
  ASSERT_TRUE((*late)->call(testing::subscribe(f.doc, 1, 4), 30)->has_ack());
  DocumentView joined(f.doc);
  waitForSnapshot(**late, joined);
  EXPECT_EQ(joined.version(), 2u);
  EXPECT_EQ(joined.surfaceHash(), seen.surfaceHash());

  // Then deltas with no gap: another edit reaches all three.
  auto second = (*editor)->call(
      testing::moveVertex(f.doc, VertexId(3, 40).packed(), 0.3, 0.3, 0.3, wire::MOVE_MODE_OFFSET), 10);
  ASSERT_TRUE(second.isOk() && second->has_ack()) << second->DebugString();
  waitForVersion(**late, joined, 3);
  waitForVersion(**viewer, seen, 3);
  EXPECT_EQ(joined.surfaceHash(), seen.surfaceHash());

  // Survives a graceful restart: the same state comes back from the store.
  EXPECT_EQ(f.server->stop(), 0);
  auto again = ServerProcess::start(f.dir + "/data");
  ASSERT_TRUE(again.isOk()) << again.status().message();
  auto back = Session::connect(again->session("back", "viewer-token-0123456789"));
  ASSERT_TRUE(back.isOk());
  ASSERT_TRUE((*back)->call(testing::openDocument(f.doc), 10)->has_ack());
  ASSERT_TRUE((*back)->call(testing::subscribe(f.doc, 1, 4), 30)->has_ack());
  DocumentView restored(f.doc);
  waitForSnapshot(**back, restored);
  EXPECT_EQ(restored.version(), 3u);
  EXPECT_EQ(restored.surfaceHash(), seen.surfaceHash());
  EXPECT_EQ(again->stop(), 0);
}

// A viewer subscribed with the profile 2,5,10 (snapshot read into `seen`)
// and an editor, both with the document open.
struct ViewerAndEditor {
  std::unique_ptr<Session> viewer, editor;
  DocumentView seen{0};
};

void connectViewerAndEditor(const Fixture& f, ViewerAndEditor& c) {
  auto viewer = Session::connect(f.server->session("viewer", "viewer-token-0123456789"));
  auto editor = Session::connect(f.server->session("editor", "editor-token-0123456789"));
  ASSERT_TRUE(viewer.isOk() && editor.isOk());
  c.viewer = std::move(*viewer);
  c.editor = std::move(*editor);
  ASSERT_TRUE(c.viewer->call(testing::openDocument(f.doc), 10)->has_ack());
  ASSERT_TRUE(c.viewer->call(testing::subscribe(f.doc, 2, 5, 10), 30)->has_ack());
  ASSERT_TRUE(c.editor->call(testing::openDocument(f.doc), 10)->has_ack());
  c.seen = DocumentView(f.doc);
  waitForSnapshot(*c.viewer, c.seen);
}

// startWithCube, then connectViewerAndEditor.
void startWithViewerAndEditor(Fixture& f, ViewerAndEditor& c, const std::string& name,
                              const std::vector<std::string>& serverArgs = {}) {
  startWithCube(f, name, serverArgs);
  if (::testing::Test::HasFatalFailure()) return;
  connectViewerAndEditor(f, c);
}

// A new subscriber's snapshot (profile 2,5,10) read into `view`.
void subscribeFresh(const Fixture& f, DocumentView& view) {
  auto late = Session::connect(f.server->session("late", "viewer-token-0123456789"));
  ASSERT_TRUE(late.isOk());
  ASSERT_TRUE((*late)->call(testing::openDocument(f.doc), 10)->has_ack());
  ASSERT_TRUE((*late)->call(testing::subscribe(f.doc, 2, 5, 10), 30)->has_ack());
  waitForSnapshot(**late, view);
}

// Edits queued together share one encode (server/document_host.h): a burst
// of pipelined edits is acked one version each, while viewers receive fewer
// deltas, some spanning several versions, with no gap, ending at the state
// a fresh subscriber sees.
TEST(Server, ABurstOfEditsIsAckedPerEditAndStreamedAsSpanningDeltas) {
  Fixture f;
  ViewerAndEditor c;
  startWithViewerAndEditor(f, c, "tessera-server-burst");
  if (::testing::Test::HasFatalFailure()) return;
  auto& viewer = c.viewer;
  auto& editor = c.editor;
  DocumentView& seen = c.seen;

  // One write holding 60 edits: the server reads them together and queues
  // them on the document's strand faster than it applies them.
  constexpr int kEdits = 60;
  std::string burst;
  for (int i = 0; i < kEdits; ++i) {
    wire::ClientMessage m =
        testing::moveVertex(f.doc, VertexId(2, static_cast<uint64_t>(i * 7 % 98)).packed(), 0.002 * (i % 5),
                            -0.001 * (i % 3), 0.0015, wire::MOVE_MODE_OFFSET);
    m.set_client_seq(1000 + static_cast<uint64_t>(i));
    auto frame = encodeFrame(m);
    ASSERT_TRUE(frame.isOk());
    burst += *frame;
  }
  ASSERT_TRUE(editor->sendRaw(burst).isOk());
  std::map<uint64_t, uint64_t> versionOfSeq;
  for (int i = 0; i < 400 && versionOfSeq.size() < kEdits; ++i) {
    auto m = editor->receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    if (m->has_reject()) FAIL() << m->DebugString();
    if (m->has_ack()) versionOfSeq[m->ack().client_seq()] = m->ack().version();
  }
  ASSERT_EQ(versionOfSeq.size(), static_cast<size_t>(kEdits));
  for (int i = 0; i < kEdits; ++i)
    EXPECT_EQ(versionOfSeq[1000 + static_cast<uint64_t>(i)], 2u + static_cast<uint64_t>(i));

  int deltas = 0, spanning = 0;
  for (int i = 0; i < 400 && seen.version() < 1 + kEdits; ++i) {
    auto m = viewer->receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    if (m->has_delta()) {
      ++deltas;
      if (m->delta().to_version() > m->delta().from_version() + 1) ++spanning;
    }
    Status applied = seen.apply(*m);
    ASSERT_TRUE(applied.isOk()) << applied.message();
  }
  EXPECT_EQ(seen.version(), 1u + kEdits);
  EXPECT_EQ(seen.gaps(), 0u);
  EXPECT_LT(deltas, kEdits);
  EXPECT_GT(spanning, 0);

  DocumentView fresh(f.doc);
  subscribeFresh(f, fresh);
  EXPECT_EQ(fresh.version(), seen.version());
  EXPECT_EQ(fresh.surfaceHash(), seen.surfaceHash());
  EXPECT_EQ(f.server->stop(), 0);
}

// A display-only subscriber (LodProfile.omit_vertex_ids) gets the same
// surface as one with ids, in fewer bytes, and its own tessellation.
TEST(Server, DisplayOnlySubscribersGetTheSameSurfaceWithoutIds) {
  Fixture f;
  ViewerAndEditor c;
  startWithViewerAndEditor(f, c, "tessera-server-display-only");
  if (::testing::Test::HasFatalFailure()) return;
  auto thin = Session::connect(f.server->session("thin", "viewer-token-0123456789"));
  ASSERT_TRUE(thin.isOk());
  ASSERT_TRUE((*thin)->call(testing::openDocument(f.doc), 10)->has_ack());
  wire::ClientMessage sub = testing::subscribe(f.doc, 2, 5, 10);
  sub.mutable_subscribe()->mutable_profile()->set_omit_vertex_ids(true);
  ASSERT_TRUE((*thin)->call(sub, 30)->has_ack());
  DocumentView thinView(f.doc);
  waitForSnapshot(**thin, thinView);
  EXPECT_LT(thinView.bytesReceived(), c.seen.bytesReceived());
  auto acked = c.editor->call(
      testing::moveVertex(f.doc, VertexId(2, 5).packed(), 0.02, 0.0, 0.01, wire::MOVE_MODE_OFFSET), 10);
  ASSERT_TRUE(acked.isOk() && acked->has_ack());
  waitForVersion(*c.viewer, c.seen, 2);
  waitForVersion(**thin, thinView, 2);
  for (const auto& [id, region] : thinView.regions()) EXPECT_TRUE(region.vertexIds.empty()) << id;
  const SurfaceMesh a = c.seen.surface(), b = thinView.surface();
  EXPECT_EQ(a.triangles.size(), b.triangles.size());
  EXPECT_EQ(a.positions.size(), b.positions.size());
  std::multiset<std::array<double, 3>> pa, pb;
  for (const Vec3& p : a.positions) pa.insert({p[0], p[1], p[2]});
  for (const Vec3& p : b.positions) pb.insert({p[0], p[1], p[2]});
  EXPECT_EQ(pa, pb);
  EXPECT_EQ(f.server->stop(), 0);
}

// A region that only moved keeps its layout, and its delta payload leaves
// the ids out (region_codec.h): the viewer keeps the ids of its copy and
// ends with the same surface, ids included, as a fresh subscriber.
TEST(Server, MovedRegionsStreamWithoutIdsAndViewersKeepTheirIds) {
  Fixture f;
  ViewerAndEditor c;
  startWithViewerAndEditor(f, c, "tessera-server-layout-ids");
  if (::testing::Test::HasFatalFailure()) return;
  int withoutIds = 0, withIds = 0;
  for (int i = 0; i < 12; ++i) {
    const VertexId v(2, static_cast<uint64_t>(i * 11 % 98));
    auto acked = c.editor->call(
        testing::moveVertex(f.doc, v.packed(), 0.004, -0.003, 0.002, wire::MOVE_MODE_OFFSET), 10);
    ASSERT_TRUE(acked.isOk() && acked->has_ack());
    while (c.seen.version() < acked->ack().version()) {
      auto m = c.viewer->receive(10);
      ASSERT_TRUE(m.isOk()) << m.status().message();
      if (m->has_delta()) {
        for (const wire::Region& r : m->delta().regions()) {
          auto decoded = decodeRegion(r.draco());
          ASSERT_TRUE(decoded.isOk()) << decoded.status().message();
          ++(decoded->first.idsInline ? withIds : withoutIds);
        }
      }
      Status applied = c.seen.apply(*m);
      ASSERT_TRUE(applied.isOk()) << applied.message();
    }
  }
  EXPECT_GT(withoutIds, 0);
  EXPECT_EQ(c.seen.gaps(), 0u);
  for (const auto& [id, region] : c.seen.regions())
    EXPECT_EQ(region.vertexIds.size(), region.positions.size()) << id;
  DocumentView fresh(f.doc);
  subscribeFresh(f, fresh);
  EXPECT_EQ(fresh.version(), c.seen.version());
  EXPECT_EQ(fresh.surfaceHash(), c.seen.surfaceHash());
  std::printf("[ measured ] 12 moves: %d delta regions without ids, %d with\n", withoutIds, withIds);
  EXPECT_EQ(f.server->stop(), 0);
}

// --delta-interval-ms: edits acked one after another within the interval
// share a delta (the first goes out at once, the rest after the interval),
// while each is acked on its own as soon as it is durable.
TEST(Server, PacedDeltasCoverTheEditsOfTheirInterval) {
  Fixture f;
  ViewerAndEditor c;
  startWithViewerAndEditor(f, c, "tessera-server-paced", {"--delta-interval-ms", "1500"});
  if (::testing::Test::HasFatalFailure()) return;
  auto& viewer = c.viewer;
  auto& editor = c.editor;
  DocumentView& seen = c.seen;
  constexpr uint64_t kEdits = 10;
  for (uint64_t i = 0; i < kEdits; ++i) {
    auto acked = editor->call(
        testing::moveVertex(f.doc, VertexId(2, i * 9).packed(), 0.002, 0.001, -0.002, wire::MOVE_MODE_OFFSET),
        10);
    ASSERT_TRUE(acked.isOk() && acked->has_ack())
        << (acked.isOk() ? acked->DebugString() : acked.status().message());
    EXPECT_EQ(acked->ack().version(), 2 + i);
  }
  std::vector<std::pair<uint64_t, uint64_t>> spans;
  for (int i = 0; i < 200 && seen.version() < 1 + kEdits; ++i) {
    auto m = viewer->receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    if (m->has_delta()) spans.emplace_back(m->delta().from_version(), m->delta().to_version());
    ASSERT_TRUE(seen.apply(*m).isOk());
  }
  EXPECT_EQ(seen.version(), 1 + kEdits);
  EXPECT_EQ(seen.gaps(), 0u);
  // Ten edits acked one by one span at most a few intervals, not ten deltas.
  ASSERT_GE(spans.size(), 2u);
  EXPECT_LE(spans.size(), 4u);
  EXPECT_EQ(spans.front(), std::make_pair(uint64_t{1}, uint64_t{2}));  // the first edit is not held back
  EXPECT_GE(spans.back().second - spans.back().first, 3u);
  DocumentView fresh(f.doc);
  subscribeFresh(f, fresh);
  EXPECT_EQ(fresh.surfaceHash(), seen.surfaceHash());
  EXPECT_EQ(f.server->stop(), 0);
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// Presence (§3): each client sees who else is connected and what they have
// selected.
TEST(Server, PresenceShowsCollaboratorsAndTheirSelections) {
  Fixture f;
  startWithCube(f, "tessera-server-presence");
  if (::testing::Test::HasFatalFailure()) return;
  auto alice = Session::connect(f.server->session("alice", "editor-token-0123456789"));
  auto bob = Session::connect(f.server->session("bob", "viewer-token-0123456789"));
  ASSERT_TRUE(alice.isOk() && bob.isOk());
  ASSERT_TRUE((*alice)->call(testing::openDocument(f.doc), 10)->has_ack());
  ASSERT_TRUE((*bob)->call(testing::openDocument(f.doc), 10)->has_ack());
  wire::ClientMessage select;
  select.mutable_select()->set_document_id(f.doc);
  select.mutable_select()->mutable_selection()->add_vertex_ids(VertexId(2, 17).packed());
  ASSERT_TRUE((*alice)->send(select).isOk());
  // Bob keeps the list as PROTOCOL 6.3 says: a full presence replaces it,
  // a change updates the participants it names and removes those who left.
  std::map<uint64_t, wire::Participant> list;
  bool seen = false, gotFull = false;
  for (int i = 0; i < 20 && !seen; ++i) {
    auto m = (*bob)->receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    if (!m->has_presence()) continue;
    if (m->presence().full()) list.clear(), gotFull = true;
    for (uint64_t left : m->presence().left_session_ids()) list.erase(left);
    for (const auto& p : m->presence().participants()) list[p.session_id()] = p;
    for (const auto& [session, p] : list) {
      if (p.name() == "alice" && p.role() == wire::ROLE_EDITOR && p.selection().vertex_ids_size() == 1 &&
          p.selection().vertex_ids(0) == VertexId(2, 17).packed()) {
        seen = list.size() == 2;
      }
    }
  }
  EXPECT_TRUE(gotFull) << "a joiner gets the whole list first";
  EXPECT_TRUE(seen);
  EXPECT_EQ(f.server->stop(), 0);
}

// The CLI talks to the server through the same client library.
TEST(Server, TheCliCreatesEditsAndListsRemotely) {
  const std::string dir = testing::makeTempDir("tessera-server-cli");
  auto server = ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk());
  std::ofstream(dir + "/token") << server->adminToken() << "\n";
  std::ofstream(dir + "/script.txt") << "move v1:20 to 0.5 0.5 1.25\noffset v3:200 by 0 0 0.04\nundo 1\n";
  const std::string remote = std::string(TESSERA_CLI_PATH) + " remote --port " +
                             std::to_string(server->port()) + " --token-file " + dir + "/token ";
  auto run = [&](const std::string& args) {
    const std::string out = dir + "/out.txt";
    const int status = std::system((remote + args + " >" + out + " 2>&1").c_str());
    return std::make_pair(WEXITSTATUS(status), testing::fileBytes(out));
  };
  auto created = run("create " + testing::sourceTestDataPath("cube.obj") + " --doc-name box --max-level 4");
  ASSERT_EQ(created.first, 0) << created.second;
  EXPECT_EQ(created.second, "1\n");
  auto edited = run("edit 1 --script " + dir + "/script.txt");
  ASSERT_EQ(edited.first, 0) << edited.second;
  // One EditBatch: the whole script is one version (cli_remote_test.cc).
  EXPECT_NE(edited.second.find("script.txt:3: edit 1\n"), std::string::npos) << edited.second;
  EXPECT_NE(edited.second.find("applied 3 commands to document 1 as version 2"), std::string::npos)
      << edited.second;
  auto listed = run("list");
  EXPECT_EQ(listed.second, "1\tbox\tversion 2\n");
  auto bad = run("edit 1 --script /nonexistent");
  EXPECT_EQ(bad.first, 1);
  auto denied = std::system((std::string(TESSERA_CLI_PATH) + " remote --port " +
                             std::to_string(server->port()) + " --token nobody-token-0123456789 create " +
                             testing::sourceTestDataPath("cube.obj") + " >/dev/null 2>&1")
                                .c_str());
  EXPECT_EQ(WEXITSTATUS(denied), 1);
  EXPECT_EQ(server->stop(), 0);
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// A client reconnects with backoff to a server that comes back,
// and a view that saw a gap recovers through a fresh snapshot.
TEST(Server, ClientsReconnectWithBackoffAndResyncAfterAGap) {
  Fixture f;
  startWithCube(f, "tessera-server-reconnect");
  if (::testing::Test::HasFatalFailure()) return;
  const uint16_t port = f.server->port();
  EXPECT_EQ(f.server->stop(), 0);
  client::SessionOptions options = f.server->session("patient", "viewer-token-0123456789");
  options.port = port;
  options.timeoutSeconds = 2;
  EXPECT_FALSE(Session::connectWithBackoff(options, 2, 0.01).isOk());

  auto again = ServerProcess::start(f.dir + "/data");
  ASSERT_TRUE(again.isOk());
  options.port = again->port();
  auto viewer = Session::connectWithBackoff(options, 5, 0.01);
  ASSERT_TRUE(viewer.isOk()) << viewer.status().message();
  ASSERT_TRUE((*viewer)->call(testing::openDocument(f.doc), 10)->has_ack());
  ASSERT_TRUE((*viewer)->call(testing::subscribe(f.doc, 1, 3), 30)->has_ack());
  DocumentView view(f.doc);
  waitForSnapshot(**viewer, view);
  // A delta that does not follow: the view refuses it and asks for a resync.
  wire::ServerMessage stray;
  stray.mutable_delta()->set_document_id(f.doc);
  stray.mutable_delta()->set_from_version(view.version() + 5);
  stray.mutable_delta()->set_to_version(view.version() + 6);
  EXPECT_FALSE(view.apply(stray).isOk());
  EXPECT_TRUE(view.needsResync());
  ASSERT_TRUE((*viewer)->call(testing::subscribe(f.doc, 1, 3), 30)->has_ack());
  waitForSnapshot(**viewer, view);
  EXPECT_FALSE(view.needsResync());
  EXPECT_EQ(again->stop(), 0);
}

}  // namespace
}  // namespace tessera
