// When deltas leave relative to durability (server/config.h,
// deltasAfterDurable): by default a delta goes out as soon as it is encoded,
// before its edit's journal commit, while the author's Ack and the
// recorders' AppliedCommand always wait for that commit; with
// --deltas-after-durable the delta waits too. A store that holds every
// commit until the test releases it makes the order observable.
#include <gtest/gtest.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <chrono>
#include <thread>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "integration/messages.h"
#include "server/document/document_host.h"
#include "support/decoding_inbox.h"
#include "support/host_only_store.h"
#include "support/test_meshes.h"

namespace tessera::server {
namespace {

bool isDelta(const wire::ServerMessage& m) {
  return m.has_delta();
}
bool isAck(const wire::ServerMessage& m) {
  return m.has_ack() && m.ack().client_seq() == 9;
}
bool isApplied(const wire::ServerMessage& m) {
  return m.has_applied_command();
}

using Inbox = testing::DecodingInbox;

class DeltaDurability : public ::testing::TestWithParam<bool> {
 protected:
  void SetUp() override {
    config_.deltaFramesPerSecond = 0;  // no pacing: the flush follows the edit
    config_.deltasAfterDurable = GetParam();
    auto mesh = importMesh(testing::sourceTestDataPath("cube.obj"));
    ASSERT_TRUE(mesh.isOk());
    auto doc = Document::create(*mesh, {.maxLevel = 4});
    ASSERT_TRUE(doc.isOk());
    host_ = std::make_shared<DocumentHost>(store::DocumentId{1}, "cube", KeyedDocument(std::move(*doc)), 1,
                                           io_.get_executor(), io_.get_executor(), store_, config_, stats_);
    thread_ = std::thread([this] { io_.run(); });
    wire::LodProfile profile;
    profile.set_base_level(1);
    profile.set_max_level(3);
    profile.set_angle_threshold_degrees(15);
    host_->join(viewer_, "viewer", wire::ROLE_VIEWER);
    wire::Subscribe request;
    *request.mutable_profile() = profile;
    host_->subscribe(viewer_, request, 1, false);
    host_->join(editor_, "editor", wire::ROLE_EDITOR);
    request.set_with_commands(true);
    host_->subscribe(editor_, request, 1, false);
    ASSERT_GE(viewer_->waitFor([](const auto& m) { return m.has_snapshot(); }, 10), 0);
    ASSERT_GE(editor_->waitFor([](const auto& m) { return m.has_snapshot(); }, 10), 0);
  }
  void TearDown() override {
    store_.completeAll(Status::ok());
    guard_.reset();
    io_.stop();
    if (thread_.joinable()) thread_.join();
  }

  ServerConfig config_;
  ServerStats stats_;
  testing::HeldStore store_;
  boost::asio::io_context io_;
  boost::asio::executor_work_guard<boost::asio::io_context::executor_type> guard_{io_.get_executor()};
  std::thread thread_;
  std::shared_ptr<DocumentHost> host_;
  std::shared_ptr<Inbox> viewer_ = std::make_shared<Inbox>(1), editor_ = std::make_shared<Inbox>(2);
};

TEST_P(DeltaDurability, AcksAndRecordersWaitForTheCommitAndDeltasOnlyIfAsked) {
  const bool afterDurable = GetParam();
  wire::ClientMessage move =
      testing::moveVertex(1, VertexId(1, 3).packed(), 0.01, 0.02, 0.0, wire::MOVE_MODE_OFFSET);
  move.set_client_seq(9);
  const size_t before = viewer_->count();
  host_->command(editor_, "editor", move);
  for (int i = 0; i < 1000 && store_.held() == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_EQ(store_.held(), 1u) << "the edit reached the journal";

  // Held commit: no ack and no recorded command, whatever the mode.
  const int early = viewer_->waitFor(isDelta, afterDurable ? 0.3 : 10, before);
  if (afterDurable) {
    EXPECT_EQ(early, -1) << "a delta went out before its edit was durable";
  } else {
    EXPECT_GE(early, 0) << "the delta waited for the commit";
  }
  EXPECT_EQ(editor_->waitFor(isAck, 0.05), -1) << "an ack before the commit";
  EXPECT_EQ(editor_->waitFor(isApplied, 0.05), -1) << "a recorded command before the commit";

  store_.completeAll(Status::ok());
  const int delta = viewer_->waitFor(isDelta, 10, before);
  ASSERT_GE(delta, 0);
  const int ack = editor_->waitFor(isAck, 10);
  const int applied = editor_->waitFor(isApplied, 10);
  const int editorDelta = editor_->waitFor(isDelta, 10);
  ASSERT_GE(ack, 0);
  ASSERT_GE(applied, 0);
  ASSERT_GE(editorDelta, 0);
  EXPECT_LT(editorDelta, applied) << "a recorder gets the command after the delta that carries it";
  EXPECT_EQ(viewer_->countOf(isDelta), 1u) << "one delta, sent once";
}

INSTANTIATE_TEST_SUITE_P(Modes, DeltaDurability, ::testing::Bool(),
                         [](const auto& info) { return info.param ? "AfterDurable" : "WhenEncoded"; });

}  // namespace
}  // namespace tessera::server
