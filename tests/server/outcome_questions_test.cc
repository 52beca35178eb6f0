// A document host answers "what became of my command?" (answerOutcomes,
// asked by a cluster node whose client's command went unanswered) only with
// what it knows. Once a journal write has failed with an unknown outcome (a
// replicated store timed out: the entry may be stored), the host cannot
// know whether the commands it was writing are in the journal, so it must
// not say "not applied": the client would send the edit again and the
// journal would hold it twice. The reloaded host answers instead.
//
// The io_context is polled on this thread, never run, so each step's work
// is done when the step returns (no waiting on time).
#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <vector>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "integration/messages.h"
#include "server/document/document_host.h"
#include "support/decoding_inbox.h"
#include "support/host_only_store.h"
#include "support/test_meshes.h"

namespace tessera::server {
namespace {

using Inbox = testing::DecodingInbox;

class OutcomeQuestions : public ::testing::Test {
 protected:
  void SetUp() override {
    config_.deltaFramesPerSecond = 0;
    auto mesh = importMesh(testing::sourceTestDataPath("cube.obj"));
    ASSERT_TRUE(mesh.isOk());
    auto doc = Document::create(*mesh, {.maxLevel = 2});
    ASSERT_TRUE(doc.isOk());
    host_ = std::make_shared<DocumentHost>(store::DocumentId{1}, "cube", KeyedDocument(std::move(*doc)), 1,
                                           io_.get_executor(), io_.get_executor(), store_, config_, stats_);
    // As a cluster node does: the commands of a write with an unknown
    // outcome go to whoever reloads the document.
    host_->onUndecided([this](DocumentHost::Undecided u) { undecided_ += static_cast<int>(u.size()); });
    host_->join(editor_, "editor", wire::ROLE_EDITOR);
    poll();
  }
  void TearDown() override {
    host_.reset();
    poll();
  }
  void poll() {
    io_.restart();
    while (io_.poll() > 0) io_.restart();
  }
  // An edit from the editor with client_seq `seq`, applied and held at its journal write.
  void editHeld(uint64_t seq) {
    wire::ClientMessage move =
        testing::moveVertex(1, VertexId(1, 3).packed(), 0.01, 0.02, 0.0, wire::MOVE_MODE_OFFSET);
    move.set_client_seq(seq);
    host_->command(editor_, "editor", move);
    poll();
  }

  ServerConfig config_;
  ServerStats stats_;
  testing::HeldStore store_;
  boost::asio::io_context io_;
  std::shared_ptr<DocumentHost> host_;
  std::shared_ptr<Inbox> editor_ = std::make_shared<Inbox>(2);
  int undecided_ = 0;
};

TEST_F(OutcomeQuestions, ACommandWhoseWriteMayBeStoredIsNeverCalledNotApplied) {
  editHeld(9);
  ASSERT_EQ(store_.held(), 1u) << "the edit reached the journal";
  host_->answerOutcomes(editor_, {9});
  poll();
  EXPECT_EQ(editor_->answersTo(9), 0) << "its write is under way: its Ack follows, no other answer";

  store_.completeAll(store::outcomeUnknownError("the test's store timed out"));
  poll();
  ASSERT_TRUE(host_->journalFailed());
  EXPECT_EQ(undecided_, 1) << "the command went to whoever reloads the document";

  host_->answerOutcomes(editor_, {9});
  poll();
  for (const auto& m : editor_->received) {
    if (m.has_reject()) ADD_FAILURE() << "answered after the failed write: " << m.reject().message();
  }
  EXPECT_EQ(editor_->answersTo(9), 0) << "only the reloaded journal can tell whether command 9 is in it";
}

TEST_F(OutcomeQuestions, DurableCommandsAreAckedAndUnknownOnesRefusedWhileTheJournalWorks) {
  editHeld(9);
  store_.completeAll(Status::ok());
  poll();
  ASSERT_EQ(editor_->answersTo(9), 1) << "the Ack of the durable edit";

  // Asked again (its Ack was lost on the way): the same Ack.
  host_->answerOutcomes(editor_, {9, 10});
  poll();
  int acks = 0;
  bool refused10 = false;
  for (const auto& m : editor_->received) {
    acks += m.has_ack() && m.ack().client_seq() == 9;
    if (m.has_reject() && m.reject().client_seq() == 10) {
      refused10 = true;
      EXPECT_EQ(m.reject().reason(), wire::REJECT_REASON_NOT_FOUND);
      EXPECT_NE(m.reject().message().find("command 10 was not applied"), std::string::npos)
          << m.reject().message();
    }
  }
  EXPECT_EQ(acks, 2);
  EXPECT_TRUE(refused10) << "a command the host never saw, with its journal working, is not applied";
}

}  // namespace
}  // namespace tessera::server
