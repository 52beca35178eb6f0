// A viewer that stops reading (docs/PROTOCOL.md §5, back-pressure): its queue stays bounded,
// merging deltas and then falling back to a resync snapshot, while a
// viewer that keeps up sees every version in order; once the slow one reads
// again it converges to the same surface.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "core/hierarchy/ids.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "integration/server_stat.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::ServerProcess;

struct Outcome {
  double queueMax = -1, merges = -1, resyncs = -1;
  uint64_t slowGaps = 0;
};

// 400 edits while one viewer reads nothing; returns the server's counters.
void runWithASlowViewer(uint64_t softBytes, uint64_t hardBytes, Outcome& outcome) {
  const std::string dir = testing::makeTempDir("tessera-server-slow");
  auto server = ServerProcess::start(
      dir + "/data", {"--queue-soft-bytes", std::to_string(softBytes), "--queue-hard-bytes",
                      std::to_string(hardBytes), "--queue-messages", "64", "--write-timeout", "120",
                      "--commands-per-second", "100000", "--send-buffer-bytes", "4096"});
  EXPECT_TRUE(server.isOk()) << server.status().message();
  if (!server.isOk()) return;
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  if (!admin.isOk()) return;
  auto created = (*admin)->call(
      testing::createDocument("cube", testing::fileBytes(testing::sourceTestDataPath("cube.obj")), "", 4),
      30);
  ASSERT_TRUE(created.isOk() && created->has_ack());
  const uint64_t doc = created->ack().document_id();
  ASSERT_TRUE((*admin)->call(testing::openDocument(doc), 10)->has_ack());

  client::SessionOptions slowOptions = server->session("slow", server->adminToken());
  slowOptions.receiveBufferBytes = 4096;
  auto slow = Session::connect(slowOptions);
  auto fast = Session::connect(server->session("fast", server->adminToken()));
  ASSERT_TRUE(slow.isOk() && fast.isOk());
  for (Session* s : {slow->get(), fast->get()}) {
    ASSERT_TRUE(s->call(testing::openDocument(doc), 10)->has_ack());
    ASSERT_TRUE(s->call(testing::subscribe(doc, 3, 4), 30)->has_ack());
  }
  DocumentView fastView(doc), slowView(doc);
  // The slow viewer reads nothing from here on; the fast one keeps up.
  uint64_t version = 1;
  for (int i = 0; i < 400; ++i) {
    const VertexId v(1 + i % 3, static_cast<uint64_t>(i * 7 % 26));
    const double d = (i % 2 ? 1 : -1) * 0.01;
    auto ack = (*admin)->call(testing::moveVertex(doc, v.packed(), d, d, d, wire::MOVE_MODE_OFFSET), 10);
    ASSERT_TRUE(ack.isOk() && ack->has_ack()) << (ack.isOk() ? ack->DebugString() : ack.status().message());
    version = ack->ack().version();
    while (fastView.version() < version) {
      auto m = (*fast)->receive(10);
      ASSERT_TRUE(m.isOk()) << m.status().message();
      Status applied = fastView.apply(*m);
      ASSERT_TRUE(applied.isOk()) << applied.message();
    }
  }
  EXPECT_EQ(fastView.gaps(), 0u);
  outcome.queueMax = testing::serverStat(**admin, "queue_bytes_max");
  outcome.merges = testing::serverStat(**admin, "delta_merges");

  // Reading again, the slow viewer converges: merged deltas and, if they
  // were dropped, a resync snapshot.
  for (int i = 0; i < 5000 && slowView.version() < version; ++i) {
    auto m = (*slow)->receive(20);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    (void)slowView.apply(*m);  // a dropped stretch shows as a gap until the resync
  }
  EXPECT_EQ(slowView.version(), version);
  EXPECT_EQ(slowView.surfaceHash(), fastView.surfaceHash());
  outcome.slowGaps = slowView.gaps();
  outcome.resyncs = testing::serverStat(**admin, "resyncs");
  std::printf(
      "slow viewer, queue limits %llu/%llu bytes: largest queue %.0f bytes, %.0f delta merges, %.0f "
      "resyncs\n",
      static_cast<unsigned long long>(softBytes), static_cast<unsigned long long>(hardBytes),
      outcome.queueMax, outcome.merges, outcome.resyncs);
  EXPECT_EQ(server->stop(), 0);
}

TEST(ServerBackpressure, ASlowViewerIsMergedThenCatchesUp) {
  Outcome o;
  runWithASlowViewer(50'000, 200'000, o);
  // Bounded: the hard limit plus at most the one frame being written.
  EXPECT_LE(o.queueMax, 200'000 + 100'000);
  EXPECT_GT(o.merges, 0);
  // Merged deltas apply without a gap: a moved region whose layout came
  // in an earlier merged delta stays behind that layout's payload.
  EXPECT_EQ(o.slowGaps, 0u);
  EXPECT_EQ(o.resyncs, 0);
}

TEST(ServerBackpressure, AViewerTooFarBehindIsResyncedWithASnapshot) {
  Outcome o;
  runWithASlowViewer(1'500, 3'000, o);
  EXPECT_LE(o.queueMax, 3'000 + 100'000);
  EXPECT_GT(o.resyncs, 0);
}

// A viewer that reads nothing at all is closed once a write has made no
// progress for --write-timeout seconds (one watchdog per connection), and
// the server keeps serving the others.
TEST(ServerBackpressure, AViewerThatStopsReadingIsClosedAfterTheWriteTimeout) {
  const std::string dir = testing::makeTempDir("tessera-server-stalled");
  auto server = ServerProcess::start(dir + "/data", {"--write-timeout", "1", "--send-buffer-bytes", "4096"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());
  auto created = (*admin)->call(
      testing::createDocument("cube", testing::fileBytes(testing::sourceTestDataPath("cube.obj")), "", 5),
      30);
  ASSERT_TRUE(created.isOk() && created->has_ack());
  const uint64_t doc = created->ack().document_id();

  client::SessionOptions stalledOptions = server->session("stalled", server->adminToken());
  stalledOptions.receiveBufferBytes = 4096;
  auto stalled = Session::connect(stalledOptions);
  ASSERT_TRUE(stalled.isOk());
  ASSERT_TRUE((*stalled)->call(testing::openDocument(doc), 10)->has_ack());
  // A level-5 snapshot (12,288 triangles) is far more than both buffers hold.
  ASSERT_TRUE((*stalled)->send(testing::subscribe(doc, 5, 5)).isOk());
  const auto start = std::chrono::steady_clock::now();
  double connections = testing::serverStat(**admin, "connections");
  EXPECT_EQ(connections, 2);
  while (connections == 2 && std::chrono::steady_clock::now() - start < std::chrono::seconds(10)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    connections = testing::serverStat(**admin, "connections");
  }
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(connections, 1) << "the stalled viewer is still connected after " << waited << " s";
  EXPECT_GE(waited, 0.9);
  EXPECT_TRUE((*admin)->call(testing::ping(), 10)->has_pong());
  // What was buffered can still be read; then the connection is closed.
  Status end = Status::ok();
  for (int i = 0; i < 1000 && end.isOk(); ++i) end = (*stalled)->receive(5).status();
  EXPECT_NE(end.message().find("connection closed"), std::string::npos) << end.message();
  EXPECT_EQ(server->stop(), 0);
}

}  // namespace
}  // namespace tessera
