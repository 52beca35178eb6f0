// Real tessera-server nodes on a real 3-server NATS JetStream cluster
// (docs/CLUSTER.md): any node serves any client, the owner's journal in JetStream is the
// truth, and every viewer on every node converges to the surface that
// journal replays to.
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <random>
#include <set>
#include <thread>

#include "cluster/cluster_run.h"
#include "core/hierarchy/ids.h"
#include "integration/messages.h"
#include "integration/server_stat.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::ClusterRun;
using testing::kClusterAngle;
using testing::kClusterBase;
using testing::kClusterMax;

TEST(ClusterServers, ViewersOnEveryNodeConvergeWithEditorsOnTwoNodes) {
  auto run = ClusterRun::start(3);
  ASSERT_TRUE(run.isOk()) << run.status().message();
  ClusterRun& c = **run;
  auto doc = c.createCube();
  ASSERT_TRUE(doc.isOk()) << doc.status().message();

  // The first to open the document takes its lease: node 0's viewer.
  std::vector<testing::ClusterViewer> viewers;
  for (int node = 0; node < 3; ++node) {
    viewers.push_back(testing::viewerOn(c, node, *doc));
    ASSERT_TRUE(viewers.back().session) << viewers.back().error;
  }
  for (auto& v : viewers) ASSERT_TRUE(testing::followUntil(*v.session, *v.view, 1, 20));
  const uint64_t before = viewers[0].view->surfaceHash();
  for (auto& v : viewers) EXPECT_EQ(v.view->surfaceHash(), before);

  // Editors on the two nodes that do not own the document: every command is
  // forwarded to node 0 and answered through their own node.
  std::vector<std::unique_ptr<Session>> editors;
  for (int node : {1, 2}) {
    auto s = Session::connect(c.session(node, "editor@" + c.nodeName(node), testing::kEditorToken));
    ASSERT_TRUE(s.isOk()) << s.status().message();
    auto opened = (*s)->call(testing::openDocument(*doc), 30);
    ASSERT_TRUE(opened.isOk() && opened->has_ack());
    editors.push_back(std::move(*s));
  }
  std::mt19937 rng(17);
  std::map<uint64_t, std::string> ackedBy;  // version -> editor
  constexpr int kEditsEach = 20;
  for (int i = 0; i < kEditsEach; ++i) {
    for (size_t e = 0; e < editors.size(); ++e) {
      auto ack = editors[e]->call(testing::smallMove(*doc, rng), 30);
      ASSERT_TRUE(ack.isOk() && ack->has_ack()) << (ack.isOk() ? ack->DebugString() : ack.status().message());
      EXPECT_TRUE(
          ackedBy.emplace(ack->ack().version(), "editor@" + c.nodeName(static_cast<int>(e) + 1)).second)
          << "version " << ack->ack().version() << " acknowledged twice";
    }
  }
  const uint64_t last = 1 + 2 * kEditsEach;
  EXPECT_EQ(ackedBy.rbegin()->first, last);

  // The journal in JetStream holds every acknowledged edit, by its author,
  // and replays to the surface every viewer shows.
  auto journal = testing::journalState(c.nats, *doc);
  ASSERT_TRUE(journal.isOk()) << journal.status().message();
  ASSERT_EQ(journal->version, last);
  for (const auto& [version, author] : ackedBy)
    EXPECT_EQ(journal->entries[version - 2].author, author) << version;
  for (auto& v : viewers) {
    ASSERT_TRUE(testing::followUntil(*v.session, *v.view, last, 30));
    EXPECT_EQ(v.view->version(), last);
    EXPECT_EQ(v.view->surfaceHash(), journal->surfaceHash);
    EXPECT_TRUE(v.view->verifySurface().isOk());
  }
  EXPECT_NE(journal->surfaceHash, before);

  // The stats say which node owns the document and that each node is a
  // distinct cluster node.
  std::set<double> numbers;
  for (int node = 0; node < 3; ++node) {
    auto admin = Session::connect(c.session(node, "admin", c.nodes[static_cast<size_t>(node)]->adminToken()));
    ASSERT_TRUE(admin.isOk());
    EXPECT_EQ(testing::serverStat(**admin, "documents_owned"), node == 0 ? 1 : 0) << c.nodeName(node);
    EXPECT_EQ(testing::serverStat(**admin, "cluster_messages_dropped"), 0) << c.nodeName(node);
    numbers.insert(testing::serverStat(**admin, "cluster_node"));
  }
  EXPECT_EQ(numbers.size(), 3u);
  EXPECT_EQ(numbers.count(0), 0u);

  // Presence across nodes: a selection made on node 1 reaches node 2's
  // viewer through the owner; when node 1 dies, node 2's viewer hears that
  // its sessions left (the owner drops a dead node's sessions).
  const uint64_t selector = viewers[1].session->sessionId();
  wire::ClientMessage select;
  select.mutable_select()->set_document_id(*doc);
  select.mutable_select()->mutable_selection()->add_vertex_ids(VertexId(0, 3).packed());
  ASSERT_TRUE(viewers[1].session->send(select).isOk());  // a selection is answered only if refused
  auto waitForPresence = [&](Session& s, const std::function<bool(const wire::Presence&)>& wanted) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (std::chrono::steady_clock::now() < deadline) {
      auto m = s.receive(0.5);
      if (m.isOk() && m->has_presence() && wanted(m->presence())) return true;
    }
    return false;
  };
  EXPECT_TRUE(waitForPresence(*viewers[2].session, [&](const wire::Presence& p) {
    for (const auto& who : p.participants()) {
      if (who.session_id() == selector && who.selection().vertex_ids_size() == 1 &&
          who.selection().vertex_ids(0) == VertexId(0, 3).packed()) {
        return true;
      }
    }
    return false;
  })) << "node 2's viewer never saw node 1's selection";
  c.nodes[1]->kill9();
  EXPECT_TRUE(waitForPresence(*viewers[2].session, [&](const wire::Presence& p) {
    for (uint64_t left : p.left_session_ids()) {
      if (left == selector) return true;
    }
    return false;
  })) << "node 1 died but its viewer stayed a participant";

  // The owner forgets other nodes' sessions once they are gone: node 1's
  // two with their node, node 2's two when they close the document.
  auto admin = Session::connect(c.session(0, "admin", c.nodes[0]->adminToken()));
  ASSERT_TRUE(admin.isOk());
  EXPECT_GE(testing::serverStat(**admin, "remote_sessions"), 2);
  for (Session* s : {viewers[2].session.get(), editors[1].get()}) {
    wire::ClientMessage close;
    close.mutable_close_document()->set_document_id(*doc);
    auto closed = s->call(close, 30);
    ASSERT_TRUE(closed.isOk() && closed->has_ack())
        << (closed.isOk() ? closed->DebugString() : closed.status().message());
  }
  double remote = -1;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < deadline && remote != 0) {
    remote = testing::serverStat(**admin, "remote_sessions");
    if (remote != 0) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  EXPECT_EQ(remote, 0) << "the owner still holds other nodes' sessions that left";
}

// With NATS servers that take at most 8 KB per message, a snapshot of a
// large profile and the deltas after it still reach a viewer on a node that
// does not own the document: node-to-node messages go in chunks.
TEST(ClusterServers, MessagesLargerThanNatsMaxPayloadCrossInChunks) {
  auto run = ClusterRun::start(2, 1500, {}, "8KB");
  ASSERT_TRUE(run.isOk()) << run.status().message();
  ClusterRun& c = **run;
  auto admin = Session::connect(c.session(0, "admin", c.nodes[0]->adminToken()));
  ASSERT_TRUE(admin.isOk());
  auto created = (*admin)->call(
      testing::createDocument("fine cube", testing::fileBytes(testing::sourceTestDataPath("cube.obj")),
                              testing::fileBytes(testing::sourceTestDataPath("cube.tags")), 5),
      30);
  ASSERT_TRUE(created.isOk() && created->has_ack()) << (created.isOk() ? created->DebugString() : "");
  const uint64_t doc = created->ack().document_id();
  std::vector<std::unique_ptr<Session>> viewers;
  std::vector<DocumentView> views;
  for (int node = 0; node < 2; ++node) {  // node 0 opens first: it owns the document
    auto s = Session::connect(c.session(node, "admin", c.nodes[static_cast<size_t>(node)]->adminToken()));
    ASSERT_TRUE(s.isOk());
    ASSERT_TRUE((*s)->call(testing::openDocument(doc), 30)->has_ack());
    auto sub = (*s)->call(testing::subscribe(doc, 5, 5, 15), 30);
    ASSERT_TRUE(sub.isOk() && sub->has_ack()) << (sub.isOk() ? sub->DebugString() : sub.status().message());
    viewers.push_back(std::move(*s));
    views.emplace_back(doc);
  }
  auto follow = [&](size_t i, uint64_t version) {
    for (int k = 0; k < 400 && (!views[i].ready() || views[i].version() < version); ++k) {
      auto m = viewers[i]->receive(10);
      if (!m.isOk()) return false;
      if (!views[i].apply(*m).isOk()) return false;
    }
    return views[i].ready() && views[i].version() >= version;
  };
  ASSERT_TRUE(follow(0, 1));
  ASSERT_TRUE(follow(1, 1)) << "the snapshot did not cross to node 1";
  std::printf("a level-5 snapshot of %lld triangles, %llu bytes, crossed NATS in messages of at most 8 KB\n",
              static_cast<long long>(views[1].numTriangles()),
              static_cast<unsigned long long>(views[1].bytesReceived()));
  EXPECT_GT(views[1].bytesReceived(), 16u * 1024);  // several chunks
  EXPECT_EQ(views[1].surfaceHash(), views[0].surfaceHash());
  EXPECT_TRUE(views[1].verifySurface().isOk());
  auto ack = viewers[1]->call(
      testing::moveVertex(doc, VertexId(1, 3).packed(), 0, 0, 0.05, wire::MOVE_MODE_OFFSET), 30);
  ASSERT_TRUE(ack.isOk() && ack->has_ack()) << (ack.isOk() ? ack->DebugString() : ack.status().message());
  ASSERT_TRUE(follow(0, ack->ack().version()));
  ASSERT_TRUE(follow(1, ack->ack().version()));
  EXPECT_EQ(views[1].surfaceHash(), views[0].surfaceHash());
}

}  // namespace
}  // namespace tessera
