// The presence of a document on its own (server/document/document_presence.h,
// docs/PROTOCOL.md §6.3): joiners and those whose queue dropped presence get
// the whole list, the others only what changed since the last broadcast;
// selections are checked before anyone sees them. No host, no timer: each
// broadcast is the test's call.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "server/document/document_presence.h"
#include "server/document/replies.h"
#include "support/decoding_inbox.h"

namespace tessera::server {
namespace {

using Inbox = testing::DecodingInbox;

// The presence messages an inbox received from index `from` on.
std::vector<wire::Presence> presences(const Inbox& inbox, size_t from = 0) {
  std::vector<wire::Presence> out;
  for (size_t i = from; i < inbox.received.size(); ++i) {
    if (inbox.received[i].has_presence()) out.push_back(inbox.received[i].presence());
  }
  return out;
}

std::vector<uint64_t> sessionsIn(const wire::Presence& p) {
  std::vector<uint64_t> out;
  for (const auto& participant : p.participants()) out.push_back(participant.session_id());
  return out;
}

class DocumentPresenceTest : public ::testing::Test {
 protected:
  // Ann (editor) and Bob (viewer) joined; the first broadcast sent.
  void joinBoth() {
    presence_.join(ann_, "ann", wire::ROLE_EDITOR);
    presence_.join(bob_, "bob", wire::ROLE_VIEWER);
    presence_.broadcast();
    annSeen_ = ann_->received.size();
    bobSeen_ = bob_->received.size();
  }

  DocumentPresence presence_{7, 1u << 20};
  std::shared_ptr<Inbox> ann_ = std::make_shared<Inbox>(1), bob_ = std::make_shared<Inbox>(2);
  size_t annSeen_ = 0, bobSeen_ = 0;
};

TEST_F(DocumentPresenceTest, JoinersGetTheWholeList) {
  joinBoth();
  for (const auto& inbox : {ann_, bob_}) {
    auto got = presences(*inbox);
    ASSERT_EQ(got.size(), 1u) << "one broadcast, one message each";
    EXPECT_TRUE(got[0].full());
    EXPECT_EQ(got[0].document_id(), 7u);
    EXPECT_EQ(sessionsIn(got[0]), (std::vector<uint64_t>{1, 2}));
    EXPECT_EQ(got[0].participants(0).name(), "ann");
    EXPECT_EQ(got[0].participants(0).role(), wire::ROLE_EDITOR);
    EXPECT_EQ(got[0].participants(1).role(), wire::ROLE_VIEWER);
  }
}

TEST_F(DocumentPresenceTest, OthersHearOnlyOfTheJoiner) {
  presence_.join(ann_, "ann", wire::ROLE_EDITOR);
  presence_.broadcast();
  const size_t seen = ann_->received.size();
  presence_.join(bob_, "bob", wire::ROLE_VIEWER);
  presence_.broadcast();
  auto annGot = presences(*ann_, seen);
  ASSERT_EQ(annGot.size(), 1u);
  EXPECT_FALSE(annGot[0].full());
  EXPECT_EQ(sessionsIn(annGot[0]), (std::vector<uint64_t>{2}));
  auto bobGot = presences(*bob_);
  ASSERT_EQ(bobGot.size(), 1u);
  EXPECT_TRUE(bobGot[0].full());
  EXPECT_EQ(sessionsIn(bobGot[0]), (std::vector<uint64_t>{1, 2}));
}

TEST_F(DocumentPresenceTest, ASelectionGoesOutAsAChange) {
  joinBoth();
  wire::Selection selection;
  selection.add_vertex_ids(VertexId(0, 3).packed());
  presence_.select(1, selection);
  presence_.broadcast();
  for (const auto& [inbox, seen] : {std::pair{ann_, annSeen_}, std::pair{bob_, bobSeen_}}) {
    auto got = presences(*inbox, seen);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_FALSE(got[0].full());
    ASSERT_EQ(sessionsIn(got[0]), (std::vector<uint64_t>{1}));
    ASSERT_EQ(got[0].participants(0).selection().vertex_ids_size(), 1);
    EXPECT_EQ(got[0].participants(0).selection().vertex_ids(0), VertexId(0, 3).packed());
  }
}

TEST_F(DocumentPresenceTest, NoChangeNoMessage) {
  joinBoth();
  presence_.broadcast();
  presence_.select(99, wire::Selection{});  // no participant: ignored
  presence_.broadcast();
  EXPECT_EQ(ann_->received.size(), annSeen_);
  EXPECT_EQ(bob_->received.size(), bobSeen_);
}

TEST_F(DocumentPresenceTest, ALeaveIsAnnouncedToTheOthers) {
  joinBoth();
  presence_.leave(2);
  EXPECT_FALSE(presence_.isParticipant(2));
  presence_.broadcast();
  auto got = presences(*ann_, annSeen_);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_FALSE(got[0].full());
  EXPECT_EQ(got[0].participants_size(), 0);
  EXPECT_EQ(std::vector<uint64_t>(got[0].left_session_ids().begin(), got[0].left_session_ids().end()),
            (std::vector<uint64_t>{2}));
  EXPECT_EQ(bob_->received.size(), bobSeen_) << "who left hears nothing more";
}

TEST_F(DocumentPresenceTest, AParticipantWhoseQueueDroppedPresenceGetsTheWholeListAgain) {
  joinBoth();
  EXPECT_TRUE(presence_.resendTo(2));
  EXPECT_FALSE(presence_.resendTo(99)) << "no participant";
  presence_.broadcast();
  auto got = presences(*bob_, bobSeen_);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_TRUE(got[0].full());
  EXPECT_EQ(sessionsIn(got[0]), (std::vector<uint64_t>{1, 2}));
  EXPECT_EQ(ann_->received.size(), annSeen_) << "nothing changed for the others";
}

TEST_F(DocumentPresenceTest, AGoneSubscriberIsSkipped) {
  joinBoth();
  bob_.reset();
  presence_.sendToAll(frameOf(rejectFor(5, internalError("journal")), 1u << 20));
  ASSERT_EQ(ann_->received.size(), annSeen_ + 1);
  EXPECT_EQ(ann_->received.back().reject().client_seq(), 5u);
}

TEST(CheckSelection, OnlyRealBoundedSelectionsPass) {
  const LevelCounts cube(8, 18, 12, 2);
  Limits limits;
  limits.selectionMaxIds = 3;
  wire::Selection fine;
  fine.add_vertex_ids(VertexId(0, 7).packed());
  fine.add_edge_ids(EdgeId(1, 3).packed());
  fine.add_face_ids(FaceId(2, 191).packed());
  EXPECT_TRUE(checkSelection(fine, cube, limits).isOk());

  wire::Selection many = fine;
  many.add_vertex_ids(VertexId(0, 1).packed());
  Status tooMany = checkSelection(many, cube, limits);
  ASSERT_FALSE(tooMany.isOk());
  EXPECT_EQ(tooMany.code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(tooMany.message().find("4 ids, above the limit of 3"), std::string::npos) << tooMany.message();

  // A vertex past level 0's, an edge below the deepest level, a face past level 2's.
  wire::Selection vertex, edge, face;
  vertex.add_vertex_ids(VertexId(0, 8).packed());
  edge.add_edge_ids(EdgeId(3, 0).packed());
  face.add_face_ids(FaceId(2, 192).packed());
  for (const wire::Selection* missing : {&vertex, &edge, &face}) {
    Status status = checkSelection(*missing, cube, limits);
    EXPECT_FALSE(status.isOk()) << missing->DebugString();
  }
}

}  // namespace
}  // namespace tessera::server
