// NATS loses quorum (issue 17 §5): two of the three NATS servers die. Edits
// are refused with an error that says what is wrong, within a bounded
// time; viewers stay connected with what they have; once the servers are
// back, the document is loaded again from JetStream and edits go on.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "cluster/cluster_run.h"
#include "core/hierarchy/ids.h"
#include "integration/messages.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::ClusterRun;
using Clock = std::chrono::steady_clock;

TEST(ClusterQuorum, WritesAreRefusedByNameAndResumeWhenNatsIsBack) {
  auto run = ClusterRun::start(1);
  ASSERT_TRUE(run.isOk()) << run.status().message();
  ClusterRun& c = **run;
  auto doc = c.createCube();
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  auto viewer = Session::connect(c.session(0, "viewer", testing::kViewerToken));
  auto editor = Session::connect(c.session(0, "editor", testing::kEditorToken));
  ASSERT_TRUE(viewer.isOk() && editor.isOk());
  ASSERT_TRUE((*viewer)->call(testing::openDocument(*doc), 30)->has_ack());
  ASSERT_TRUE((*viewer)->call(testing::subscribe(*doc, testing::kClusterBase, testing::kClusterMax,
                                                 testing::kClusterAngle), 30)->has_ack());
  ASSERT_TRUE((*editor)->call(testing::openDocument(*doc), 30)->has_ack());
  DocumentView view(*doc);
  auto move = [&](double dz) {
    return testing::moveVertex(*doc, VertexId(1, 7).packed(), 0, 0, dz, wire::MOVE_MODE_OFFSET);
  };
  auto first = (*editor)->call(move(0.01), 30);
  ASSERT_TRUE(first.isOk() && first->has_ack());
  ASSERT_TRUE(testing::followUntil(**viewer, view, first->ack().version(), 20));

  c.nats.kill9(1);
  c.nats.kill9(2);
  // The first edit's journal write times out: its outcome is unknown until
  // NATS is back, so it is answered then. Meanwhile the participants are
  // told why, and later edits are refused at once, saying why.
  const auto start = Clock::now();
  auto pending = (*editor)->send(move(0.01));
  ASSERT_TRUE(pending.isOk());
  bool told = false;
  std::string received;  // what came instead, for the failure message
  for (int i = 0; i < 60 && !told; ++i) {
    auto m = (*editor)->receive(0.5);
    if (!m.isOk()) continue;
    told = m->has_error() && m->error().message().find("majority of the NATS servers") != std::string::npos;
    if (!told) received += m->ShortDebugString() + "\n";
  }
  const double took = std::chrono::duration<double>(Clock::now() - start).count();
  ASSERT_TRUE(told) << "no error naming the lost quorum; received instead:\n" << received;
  std::printf("told of the lost quorum after %.2f s\n", took);
  EXPECT_LT(took, 15.0);
  auto refused = (*editor)->call(move(0.01), 30);
  ASSERT_TRUE(refused.isOk()) << refused.status().message();
  ASSERT_TRUE(refused->has_reject()) << refused->DebugString();
  EXPECT_NE(refused->reject().message().find("majority of the NATS servers"), std::string::npos)
      << refused->reject().message();
  std::printf("an edit without NATS quorum: %s\n", refused->reject().message().c_str());
  // The viewer is still connected and still holds the surface it had.
  EXPECT_TRUE((*viewer)->send(testing::ping()).isOk());
  EXPECT_TRUE(view.ready());

  ASSERT_TRUE(c.nats.restart(1).isOk());
  ASSERT_TRUE(c.nats.restart(2).isOk());
  // Edits go on once JetStream has its quorum again and the node reloaded.
  std::optional<uint64_t> acked;
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (!acked && Clock::now() < deadline) {
    auto r = (*editor)->call(move(0.01), 5);
    if (r.isOk() && r->has_ack()) acked = r->ack().version();
    if (!acked) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  ASSERT_TRUE(acked.has_value()) << "edits did not resume after NATS got its quorum back";
  // The edit whose write timed out got its answer from the reloaded
  // journal: an Ack if the write was stored, a Reject saying it was not.
  bool answered = false;
  for (int i = 0; i < 40 && !answered; ++i) {
    auto m = (*editor)->receive(0.5);
    if (!m.isOk()) continue;
    answered = (m->has_ack() && m->ack().client_seq() == *pending) ||
               (m->has_reject() && m->reject().client_seq() == *pending &&
                m->reject().message().find("was not applied") != std::string::npos);
  }
  EXPECT_TRUE(answered) << "the edit made while NATS had no quorum was never answered";
  auto journal = testing::journalState(c.nats, *doc);
  ASSERT_TRUE(journal.isOk()) << journal.status().message();
  EXPECT_EQ(journal->version, *acked);
  ASSERT_TRUE(testing::followUntil(**viewer, view, *acked, 30));
  EXPECT_EQ(view.surfaceHash(), journal->surfaceHash);
}

}  // namespace
}  // namespace tessera
