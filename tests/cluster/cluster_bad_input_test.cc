// Bad input on the cluster's subjects (docs/CLUSTER.md "Tests"): whatever another
// NATS client publishes on a node's subjects, the node logs it, drops it and
// goes on serving; garbage on a document's journal subject makes that
// document refuse edits by name, never a crash.
#include <gtest/gtest.h>

#include <nats/nats.h>

#include <fstream>
#include <sstream>

#include "cluster/cluster_run.h"
#include "integration/messages.h"
#include "integration/server_stat.h"
#include "protocol/cluster.pb.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::ClusterRun;

void publish(natsConnection* nc, const std::string& subject, const std::string& bytes) {
  ASSERT_EQ(natsConnection_Publish(nc, subject.c_str(), bytes.data(), static_cast<int>(bytes.size())),
            NATS_OK);
}

std::string logOf(const ClusterRun& run, int node) {
  std::ifstream in(run.directory + "/" + run.nodeName(node) + ".log");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ClusterBadInput, GarbageOnClusterSubjectsIsLoggedAndDropped) {
  auto run = ClusterRun::start(2);
  ASSERT_TRUE(run.isOk()) << run.status().message();
  ClusterRun& c = **run;
  auto doc = c.createCube();
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  // A viewer on node 1 of a document node 0 owns: frames cross the cluster.
  auto owner = Session::connect(c.session(0, "editor@node0", testing::kEditorToken));
  auto viewer = Session::connect(c.session(1, "viewer@node1", testing::kViewerToken));
  ASSERT_TRUE(owner.isOk() && viewer.isOk());
  ASSERT_TRUE((*owner)->call(testing::openDocument(*doc), 30)->has_ack());
  ASSERT_TRUE((*viewer)->call(testing::openDocument(*doc), 30)->has_ack());
  ASSERT_TRUE((*viewer)
                  ->call(testing::subscribe(*doc, testing::kClusterBase, testing::kClusterMax,
                                            testing::kClusterAngle),
                         30)
                  ->has_ack());
  DocumentView view(*doc);
  ASSERT_TRUE(testing::followUntil(**viewer, view, 1, 20));

  natsConnection* nc = nullptr;
  ASSERT_EQ(natsConnection_ConnectTo(&nc, c.nats.urls().c_str()), NATS_OK);
  // Not protobuf; protobuf of the wrong message; a Forward without a kind;
  // a Forward for a document nobody owns; Frames whose frame is not one;
  // a delta whose region flags do not match; an empty NodeMessage.
  cluster::Forward noKind;
  noKind.set_via_node("node1");
  noKind.set_session_id(5);
  noKind.set_document_id(*doc);
  cluster::Forward unknownDocument = noKind;
  unknownDocument.set_kind(cluster::Forward::KIND_COMMAND);
  unknownDocument.set_document_id(999);
  cluster::NodeMessage badFrame;
  badFrame.mutable_frames()->add_session_ids(1);
  badFrame.mutable_frames()->set_frame(std::string("\x00\x00\x00\x09short", 9));
  cluster::NodeMessage badDelta;
  wire::ServerMessage delta;
  delta.mutable_delta()->set_document_id(*doc);
  delta.mutable_delta()->add_regions()->set_draco("x");
  const std::string payload = delta.SerializeAsString();
  std::string frame(4, '\0');
  frame[3] = static_cast<char>(payload.size());
  badDelta.mutable_frames()->add_session_ids(1);
  badDelta.mutable_frames()->set_frame(frame + payload);
  badDelta.mutable_frames()->set_is_delta(true);
  // Whole messages start with 0x00, chunks with 0x01 (message_chunks.h):
  // a chunk out of order, and one whose header is cut short, too.
  const std::string whole(1, '\0');
  std::string lateChunk(
      "\x01\x03"
      "bad",
      5);
  lateChunk += std::string("\x07\0\0\0\0\0\0\0", 8) + std::string("\x01\0\0\0", 4) +
               std::string("\x02\0\0\0", 4) + "data";
  for (int node = 0; node < 2; ++node) {
    const std::string forward = "tessera.node." + c.nodeName(node) + ".forward";
    const std::string frames = "tessera.node." + c.nodeName(node) + ".frames";
    publish(nc, forward, "\xff\xfe garbage \x01");
    publish(nc, forward, whole + "\xff\xfe garbage \x01");
    publish(nc, forward, whole + delta.SerializeAsString());
    publish(nc, forward, whole + noKind.SerializeAsString());
    publish(nc, forward, whole + unknownDocument.SerializeAsString());
    publish(nc, forward, lateChunk);
    publish(nc, frames, std::string("\x01\x05", 2));
    publish(nc, frames, whole + "\x0a\xff\xff\xff\xff\x0f");
    publish(nc, frames, whole + badFrame.SerializeAsString());
    publish(nc, frames, whole + badDelta.SerializeAsString());
    publish(nc, frames, whole + cluster::NodeMessage().SerializeAsString());
  }
  ASSERT_EQ(natsConnection_Flush(nc), NATS_OK);

  // Both nodes still serve: an edit on node 0 reaches the viewer on node 1.
  auto ack = (*owner)->call(
      testing::moveVertex(*doc, VertexId(1, 3).packed(), 0, 0, 0.01, wire::MOVE_MODE_OFFSET), 30);
  ASSERT_TRUE(ack.isOk() && ack->has_ack()) << (ack.isOk() ? ack->DebugString() : ack.status().message());
  ASSERT_TRUE(testing::followUntil(**viewer, view, ack->ack().version(), 20));
  auto journal = testing::journalState(c.nats, *doc);
  ASSERT_TRUE(journal.isOk());
  EXPECT_EQ(view.surfaceHash(), journal->surfaceHash);
  for (int node = 0; node < 2; ++node) {
    const std::string log = logOf(c, node);
    EXPECT_NE(log.find("\"cluster_message_dropped\""), std::string::npos) << c.nodeName(node);
    EXPECT_NE(log.find("not a cluster message (first byte 255)"), std::string::npos) << c.nodeName(node);
    EXPECT_NE(log.find("not a cluster Forward"), std::string::npos) << c.nodeName(node);
    EXPECT_NE(log.find("cluster chunk 1 of 2 from bad out of order"), std::string::npos) << c.nodeName(node);
    EXPECT_NE(log.find("a cluster chunk without its header"), std::string::npos) << c.nodeName(node);
    EXPECT_NE(log.find("a Forward without its kind"), std::string::npos) << c.nodeName(node);
    EXPECT_NE(log.find("a cluster frame announces 9 bytes but carries 5"), std::string::npos)
        << c.nodeName(node);
    EXPECT_NE(log.find("region flags"), std::string::npos) << c.nodeName(node);
  }

  // Garbage appended to the document's journal subject: the owner's next
  // append is refused (the subject moved on), the document is reloaded and
  // refused by name, and the node goes on serving another document.
  // (A JetStream publish: stored once it returns, so the owner's next append
  // comes after it.)
  jsCtx* js = nullptr;
  ASSERT_EQ(natsConnection_JetStream(&js, nc, nullptr), NATS_OK);
  const std::string garbage = "not a journal message";
  const std::string subject = "tessera.journal." + std::to_string(*doc);
  jsPubAck* stored = nullptr;
  ASSERT_EQ(js_Publish(&stored, js, subject.c_str(), garbage.data(), static_cast<int>(garbage.size()),
                       nullptr, nullptr),
            NATS_OK);
  jsPubAck_Destroy(stored);
  jsCtx_Destroy(js);
  auto refused = (*owner)->call(
      testing::moveVertex(*doc, VertexId(1, 4).packed(), 0, 0, 0.01, wire::MOVE_MODE_OFFSET), 30);
  ASSERT_TRUE(refused.isOk()) << refused.status().message();
  EXPECT_TRUE(refused->has_reject()) << refused->DebugString();
  auto second = c.createCube();
  ASSERT_TRUE(second.isOk()) << second.status().message();
  auto admin = Session::connect(c.session(0, "admin", c.nodes[0]->adminToken()));
  ASSERT_TRUE(admin.isOk());
  ASSERT_TRUE((*admin)->call(testing::openDocument(*second), 30)->has_ack());
  auto fine = (*admin)->call(
      testing::moveVertex(*second, VertexId(1, 4).packed(), 0, 0, 0.01, wire::MOVE_MODE_OFFSET), 30);
  ASSERT_TRUE(fine.isOk() && fine->has_ack())
      << (fine.isOk() ? fine->DebugString() : fine.status().message());
  // The viewer on node 1 is told the document has no owner, and why; then
  // opening it names the message that does not decode.
  bool told = false;
  for (int i = 0; i < 40 && !told; ++i) {
    auto m = (*viewer)->receive(0.5);
    told = m.isOk() && m->has_error() &&
           m->error().message().find("not a Tessera journal message") != std::string::npos;
  }
  EXPECT_TRUE(told) << "the viewer was not told why the document stopped";
  auto reopen = Session::connect(c.session(1, "viewer@node1", testing::kViewerToken));
  ASSERT_TRUE(reopen.isOk());
  auto damaged = (*reopen)->call(testing::openDocument(*doc), 30);
  ASSERT_TRUE(damaged.isOk() && damaged->has_reject()) << (damaged.isOk() ? damaged->DebugString() : "");
  // (Its stream sequence depends on how many fences takeovers wrote.)
  EXPECT_NE(damaged->reject().message().find("document 1, stream sequence "), std::string::npos)
      << damaged->reject().message();
  EXPECT_NE(
      damaged->reject().message().find(": not a Tessera journal message (21 bytes without the TJ2 header)"),
      std::string::npos)
      << damaged->reject().message();
  natsConnection_Destroy(nc);
  EXPECT_GE(testing::serverStat(**admin, "connections"), 1);
}

}  // namespace
}  // namespace tessera
