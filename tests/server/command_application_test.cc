// The intake stage on its own (server/document/command_application.h): a
// command becomes a document change, an EditBatch is all or nothing, and a
// refused command leaves the document as it was, limit for limit; the
// Reject it gets names the refused command and its reason
// (docs/PROTOCOL.md §5).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/document/document.h"
#include "integration/messages.h"
#include "server/document/command_application.h"
#include "server/document/replies.h"
#include "support/test_meshes.h"

namespace tessera::server {
namespace {

constexpr store::DocumentId kDoc{1};

class CommandApplication : public ::testing::Test {
 protected:
  void SetUp() override {
    auto doc = testing::cubeDocument(2);
    ASSERT_TRUE(doc.isOk()) << doc.status().message();
    keyed_.emplace(std::move(*doc));
  }
  std::vector<Vec3> limits() const {
    auto surface = keyed_->key0().surface(2, SurfaceKind::kLimit);
    EXPECT_TRUE(surface.isOk());
    return surface.isOk() ? surface->positions : std::vector<Vec3>{};
  }
  static wire::ClientMessage move(uint32_t level, uint64_t index, double dx) {
    return testing::moveVertex(kDoc.value, VertexId(level, index).packed(), dx, 0.0, 0.0,
                               wire::MOVE_MODE_OFFSET);
  }
  static void add(wire::EditBatch& batch, const wire::ClientMessage& one) {
    *batch.add_commands()->mutable_move_vertex() = one.move_vertex();
  }

  std::optional<KeyedDocument> keyed_;
};

TEST_F(CommandApplication, AnEditChangesTheDocumentAndNamesItsLimits) {
  const std::vector<Vec3> before = limits();
  AppliedChange applied;
  ASSERT_TRUE(applyCommand(*keyed_, kDoc, move(1, 3, 0.05), applied).isOk());
  EXPECT_EQ(applied.entry.kind, JournalEntry::Kind::kEdit);
  ASSERT_EQ(applied.editIds.size(), 1u);
  EXPECT_EQ(keyed_->key0().edits().size(), 1u);
  EXPECT_FALSE(applied.limits.empty());
  EXPECT_NE(limits(), before);
}

TEST_F(CommandApplication, ARefusedBatchLeavesEveryLimitAsItWas) {
  const std::vector<Vec3> before = limits();
  wire::ClientMessage message;
  add(*message.mutable_edit_batch(), move(1, 3, 0.05));
  add(*message.mutable_edit_batch(), move(0, 2, 0.05));
  add(*message.mutable_edit_batch(), move(1, 999999, 0.05));  // no such vertex
  AppliedChange applied;
  Status status = applyCommand(*keyed_, kDoc, message, applied);
  ASSERT_FALSE(status.isOk());
  EXPECT_EQ(applied.failedIndex, 3u);
  EXPECT_NE(status.message().find("edit batch, command 3 of 3"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("nothing of the batch was applied"), std::string::npos) << status.message();
  EXPECT_TRUE(keyed_->key0().edits().empty());
  EXPECT_EQ(limits(), before) << "the two applied moves must be taken back bit for bit";

  const wire::ServerMessage reject = rejectForCommand(9, message, applied.failedIndex, status);
  ASSERT_TRUE(reject.has_reject());
  EXPECT_EQ(reject.reject().client_seq(), 9u);
  EXPECT_EQ(reject.reject().batch_index(), 3u);
}

TEST_F(CommandApplication, ABatchForAnotherDocumentIsRefusedNamingBoth) {
  wire::ClientMessage message;
  add(*message.mutable_edit_batch(),
      testing::moveVertex(5, VertexId(1, 3).packed(), 0.05, 0, 0, wire::MOVE_MODE_OFFSET));
  AppliedChange applied;
  Status status = applyCommand(*keyed_, kDoc, message, applied);
  ASSERT_FALSE(status.isOk());
  EXPECT_NE(status.message().find("names document 5, the batch is for 1"), std::string::npos)
      << status.message();
  EXPECT_EQ(applied.failedIndex, 1u);
}

TEST_F(CommandApplication, AnEmptyBatchIsRefused) {
  wire::ClientMessage message;
  message.mutable_edit_batch();
  AppliedChange applied;
  Status status = applyCommand(*keyed_, kDoc, message, applied);
  ASSERT_FALSE(status.isOk());
  EXPECT_EQ(status.message(), "edit batch: no commands");
}

TEST_F(CommandApplication, UndoingAnUndoneEditIsAnInvalidState) {
  AppliedChange made;
  ASSERT_TRUE(applyCommand(*keyed_, kDoc, move(1, 3, 0.05), made).isOk());
  wire::ClientMessage undo;
  undo.mutable_undo()->set_document_id(kDoc.value);
  undo.mutable_undo()->set_edit_id(made.editIds.at(0));
  AppliedChange first;
  ASSERT_TRUE(applyCommand(*keyed_, kDoc, undo, first).isOk());
  AppliedChange again;
  Status status = applyCommand(*keyed_, kDoc, undo, again);
  ASSERT_FALSE(status.isOk());
  EXPECT_EQ(rejectForCommand(3, undo, again.failedIndex, status).reject().reason(),
            wire::REJECT_REASON_INVALID_STATE);

  // The same inside a batch, after a move that is taken back.
  wire::ClientMessage batch;
  add(*batch.mutable_edit_batch(), move(1, 3, 0.07));
  *batch.mutable_edit_batch()->add_commands()->mutable_undo() = undo.undo();
  const std::vector<Vec3> before = limits();
  AppliedChange inBatch;
  Status refused = applyCommand(*keyed_, kDoc, batch, inBatch);
  ASSERT_FALSE(refused.isOk());
  const wire::ServerMessage reject = rejectForCommand(4, batch, inBatch.failedIndex, refused);
  EXPECT_EQ(reject.reject().reason(), wire::REJECT_REASON_INVALID_STATE);
  EXPECT_EQ(reject.reject().batch_index(), 2u);
  EXPECT_EQ(limits(), before);

  // An edit id the document never made is not found, not a state.
  wire::ClientMessage unknown = undo;
  unknown.mutable_undo()->set_edit_id(777);
  AppliedChange none;
  Status missing = applyCommand(*keyed_, kDoc, unknown, none);
  ASSERT_FALSE(missing.isOk());
  EXPECT_EQ(rejectForCommand(5, unknown, 0, missing).reject().reason(), wire::REJECT_REASON_NOT_FOUND);
}

TEST_F(CommandApplication, RetractingAnAppliedEditRestoresItsLimits) {
  const std::vector<Vec3> before = limits();
  AppliedChange applied;
  ASSERT_TRUE(applyCommand(*keyed_, kDoc, move(0, 2, 0.1), applied).isOk());
  ASSERT_NE(limits(), before);
  ASSERT_TRUE(retractCommand(*keyed_, applied.entry).isOk());
  EXPECT_EQ(limits(), before);
  EXPECT_TRUE(keyed_->key0().edits().empty());
}

}  // namespace
}  // namespace tessera::server
