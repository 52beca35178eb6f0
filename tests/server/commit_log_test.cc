// The commit stage of a document on its own (server/document/commit_log.h):
// an Ack only once the journal holds the edit, a delta held until every edit
// it carries is durable, a recorder's command after the delta that carries
// it, a failed journal write that refuses what was not acknowledged (or hands
// it on when the store cannot know), and the answers to "what became of my
// command". No host, no threads: each call's effect is there when it returns.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "server/document/commit_log.h"
#include "support/decoding_inbox.h"

namespace tessera::server {
namespace {

using Inbox = testing::DecodingInbox;

class CommitLogTest : public ::testing::Test {
 protected:
  // The command applied as `version` by the author, client_seq `seq`, edit `editId`.
  PendingEdit edit(uint64_t version, uint64_t seq, uint64_t editId, std::vector<uint64_t> batchIds = {}) {
    wire::ClientMessage command;
    command.set_client_seq(seq);
    command.mutable_move_vertex()->set_document_id(7);
    return {version,
            author_,
            author_->sessionId(),
            seq,
            editId,
            std::move(batchIds),
            std::chrono::steady_clock::now(),
            command,
            "author"};
  }
  // A flush up to `version`; its delivery is logged as "delta <version>".
  FlushBatch batch(uint64_t version) { return {version, {}, {}}; }
  std::function<void(FlushBatch&)> sender() {
    return [this](FlushBatch& b) { delivered_.push_back(b.toVersion); };
  }
  std::vector<const wire::ServerMessage*> acks(const Inbox& inbox) const {
    std::vector<const wire::ServerMessage*> out;
    for (const auto& m : inbox.received)
      if (m.has_ack()) out.push_back(&m);
    return out;
  }

  ServerStats stats_;
  CommitLog log_{store::DocumentId{7}, 1, 1u << 20, stats_};
  std::shared_ptr<Inbox> author_ = std::make_shared<Inbox>(40);
  std::vector<uint64_t> delivered_;
};

TEST_F(CommitLogTest, AcksOnlyWhatTheJournalHolds) {
  log_.applied(edit(2, 100, 11));
  log_.applied(edit(3, 101, 12));
  log_.release(sender());
  EXPECT_TRUE(acks(*author_).empty()) << "nothing is durable yet";

  log_.durable(2);
  log_.release(sender());
  ASSERT_EQ(acks(*author_).size(), 1u);
  const wire::Ack& first = acks(*author_)[0]->ack();
  EXPECT_EQ(first.client_seq(), 100u);
  EXPECT_EQ(first.document_id(), 7u);
  EXPECT_EQ(first.version(), 2u);
  EXPECT_EQ(first.edit_id(), 11u);

  log_.durable(3);
  log_.release(sender());
  log_.release(sender());  // again: nothing is acknowledged twice
  ASSERT_EQ(acks(*author_).size(), 2u);
  EXPECT_EQ(acks(*author_)[1]->ack().client_seq(), 101u);
  EXPECT_EQ(acks(*author_)[1]->ack().version(), 3u);
}

TEST_F(CommitLogTest, ABatchAcksWithEveryEditId) {
  log_.applied(edit(2, 100, 13, {11, 12, 13}));
  log_.durable(2);
  log_.release(sender());
  ASSERT_EQ(acks(*author_).size(), 1u);
  const wire::Ack& ack = acks(*author_)[0]->ack();
  EXPECT_EQ(ack.edit_id(), 13u);
  EXPECT_EQ(std::vector<uint64_t>(ack.edit_ids().begin(), ack.edit_ids().end()),
            (std::vector<uint64_t>{11, 12, 13}));
}

TEST_F(CommitLogTest, ADeltaWaitsForEveryEditItCarries) {
  log_.applied(edit(2, 100, 11));
  log_.applied(edit(3, 101, 12));
  log_.flushed(batch(3));  // one delta for versions 2 and 3
  log_.durable(2);
  log_.release(sender());
  EXPECT_TRUE(delivered_.empty()) << "version 3 is not durable yet";
  log_.durable(3);
  log_.release(sender());
  EXPECT_EQ(delivered_, (std::vector<uint64_t>{3}));
  EXPECT_TRUE(log_.atRest(3));
  EXPECT_FALSE(log_.atRest(4)) << "version 4 applied but not durable";
}

TEST_F(CommitLogTest, ARecorderGetsEachLaterCommandAfterItsDelta) {
  auto recorder = std::make_shared<Inbox>(50);
  log_.record(50, recorder, 2);  // subscribed when the document was at version 2
  log_.applied(edit(2, 100, 11));
  log_.flushed(batch(2));
  log_.applied(edit(3, 101, 12));
  log_.flushed(batch(3));
  // The recorder's commands are logged in the same sequence as the deltas.
  log_.durable(3);
  size_t appliedBeforeDelta3 = 0;
  log_.release([&](FlushBatch& b) {
    delivered_.push_back(b.toVersion);
    if (b.toVersion == 3) appliedBeforeDelta3 = recorder->received.size();
  });
  EXPECT_EQ(delivered_, (std::vector<uint64_t>{2, 3}));
  ASSERT_EQ(recorder->received.size(), 1u) << "version 2 is not after the recorder's subscribe";
  EXPECT_EQ(appliedBeforeDelta3, 0u) << "version 3's command came before its delta";
  const wire::AppliedCommand& a = recorder->received[0].applied_command();
  EXPECT_EQ(a.version(), 3u);
  EXPECT_EQ(a.edit_id(), 12u);
  EXPECT_EQ(a.author_session_id(), 40u);
  EXPECT_EQ(a.author_name(), "author");
  EXPECT_EQ(a.document_id(), 7u);
  EXPECT_TRUE(a.has_move_vertex());

  log_.stopRecording(50);
  log_.applied(edit(4, 102, 13));
  log_.flushed(batch(4));
  log_.durable(4);
  log_.release(sender());
  EXPECT_EQ(recorder->received.size(), 1u) << "it stopped recording";
}

TEST_F(CommitLogTest, AFailedWriteRefusesWhatWasNotAcknowledged) {
  log_.applied(edit(2, 100, 11));
  log_.applied(edit(3, 101, 12));
  log_.durable(2);
  log_.release(sender());
  auto undecided = log_.failed(ioError("disk full"), false);
  EXPECT_TRUE(undecided.empty());
  ASSERT_EQ(author_->received.size(), 2u);  // the Ack of 100, then the Reject of 101
  const wire::ServerMessage& reject = author_->received[1];
  ASSERT_TRUE(reject.has_reject());
  EXPECT_EQ(reject.reject().client_seq(), 101u);
  EXPECT_EQ(reject.reject().reason(), wire::REJECT_REASON_INTERNAL);
  EXPECT_NE(reject.reject().message().find("disk full"), std::string::npos) << reject.reject().message();
  EXPECT_TRUE(log_.atRest(2));
}

TEST_F(CommitLogTest, AWriteOfUnknownOutcomeIsHandedOnNotRefused) {
  log_.applied(edit(2, 100, 11));
  log_.applied(edit(3, 101, 12));
  auto undecided = log_.failed(store::outcomeUnknownError("journal append timed out"), true);
  ASSERT_EQ(undecided.size(), 2u);
  EXPECT_EQ(undecided[0].second, 100u);
  EXPECT_EQ(undecided[1].second, 101u);
  EXPECT_TRUE(author_->received.empty()) << "neither lost nor stored is known: nothing is said";
  // Asked later, this host does not know either: whoever reloads answers.
  EXPECT_FALSE(log_.outcomeOf({40, 100}, true).has_value());
}

TEST_F(CommitLogTest, AnswersWhatBecameOfACommand) {
  log_.applied(edit(2, 100, 11));
  EXPECT_FALSE(log_.outcomeOf({40, 100}, false).has_value()) << "still waiting: its Ack follows";
  log_.durable(2);
  log_.release(sender());
  auto acked = log_.outcomeOf({40, 100}, false);
  ASSERT_TRUE(acked && acked->has_ack());
  EXPECT_EQ(acked->ack().version(), 2u);
  EXPECT_EQ(acked->ack().edit_id(), 11u);

  auto unknown = log_.outcomeOf({40, 555}, false);
  ASSERT_TRUE(unknown && unknown->has_reject());
  EXPECT_EQ(unknown->reject().reason(), wire::REJECT_REASON_NOT_FOUND);
  EXPECT_EQ(unknown->reject().client_seq(), 555u);

  // Loaded with the journal (a cluster node took the document).
  log_.setLoadedOutcomes({{{41, 9}, CommandOutcome{5, {21, 22}}}}, 4);
  auto loaded = log_.outcomeOf({41, 9}, false);
  ASSERT_TRUE(loaded && loaded->has_ack());
  EXPECT_EQ(loaded->ack().version(), 5u);
  EXPECT_EQ(loaded->ack().edit_ids_size(), 2);
}

}  // namespace
}  // namespace tessera::server
