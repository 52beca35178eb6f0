// The pieces beside tessera-view's Connection (client/view/connection.h),
// each on its own with no server and no window: the pacing of what it sends,
// the edit-to-delta latency, the collaborators from Presence, a 2D morph's
// key positions, and the morph key carried by the undo history's edit ids.
// Expected values are worked out by hand in the comments.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <vector>

#include "client/view/collaborators.h"
#include "client/view/latency_tracker.h"
#include "client/view/morph_key_follower.h"
#include "client/view/pacer.h"
#include "client/view/undo_history.h"

namespace tessera::view {
namespace {

using std::chrono::milliseconds;

int takeAll(Pacer& p) {
  int n = 0;
  while (p.take()) ++n;
  return n;
}

TEST(ViewPacer, StartsFullEarnsTokensAtItsRateAndNeverHoldsMoreThanABurst) {
  const Pacer::Clock::time_point t0{};
  Pacer p(t0, /*rate=*/10, /*burst=*/3);
  EXPECT_EQ(takeAll(p), 3);  // full: a burst of 3
  p.refill(t0);
  EXPECT_EQ(takeAll(p), 0);  // no time passed, no token
  p.refill(t0 + milliseconds(150));
  EXPECT_EQ(takeAll(p), 1);  // 10/s * 0.15 s = 1.5 tokens: one command, half a token left
  EXPECT_NEAR(p.tokens(), 0.5, 1e-9);
  p.refill(t0 + milliseconds(250));
  EXPECT_EQ(takeAll(p), 1);  // 0.5 + 10/s * 0.1 s = 1.5 tokens
  p.refill(t0 + milliseconds(10250));
  EXPECT_EQ(takeAll(p), 3);  // 100 tokens earned in 10 s, capped at the burst of 3
}

TEST(ViewPacer, TheViewersPaceIs150ASecondInBurstsOf150) {
  const Pacer::Clock::time_point t0{};
  Pacer p(t0);
  EXPECT_EQ(takeAll(p), 150);
  p.refill(t0 + milliseconds(210));
  EXPECT_EQ(takeAll(p), 31);  // 150/s * 0.21 s = 31.5 tokens
  p.refill(t0 + milliseconds(60210));
  EXPECT_EQ(takeAll(p), 150);
}

TEST(ViewLatencyTracker, MeasuresFromTheSendToTheDeltaReachingTheAckedVersion) {
  const LatencyTracker::Clock::time_point t0{};
  LatencyTracker l;
  EXPECT_EQ(l.summary().samples, 0u);
  EXPECT_EQ(l.summary().lastMs, -1);

  // The Ack first: version 5, the view at 4; its delta 4..5 comes 30 ms after the send.
  l.acked(5, t0, 4);
  EXPECT_EQ(l.awaitingDelta(), 1u);
  l.delta(4, 5, true, t0 + milliseconds(30));
  EXPECT_EQ(l.awaitingDelta(), 0u);
  EXPECT_EQ(l.summary().samples, 1u);
  EXPECT_DOUBLE_EQ(l.summary().lastMs, 30);

  // A merged delta 5..7 reaches two Acks, sent at 100 and 110 ms, at 150 ms:
  // 50 ms, then 40 ms.
  l.acked(6, t0 + milliseconds(100), 5);
  l.acked(7, t0 + milliseconds(110), 5);
  EXPECT_EQ(l.awaitingDelta(), 2u);
  l.delta(5, 7, true, t0 + milliseconds(150));
  EXPECT_EQ(l.awaitingDelta(), 0u);
  EXPECT_EQ(l.summary().samples, 3u);
  EXPECT_DOUBLE_EQ(l.summary().lastMs, 40);
  EXPECT_DOUBLE_EQ(l.summary().maxMs, 50);

  // The delta first: this session's delta 7..8 at 200 ms is remembered; the
  // Ack of the edit sent at 190 ms comes with the view at 8: 10 ms.
  l.delta(7, 8, true, t0 + milliseconds(200));
  l.acked(8, t0 + milliseconds(190), 8);
  EXPECT_EQ(l.summary().samples, 4u);
  EXPECT_DOUBLE_EQ(l.summary().lastMs, 10);
  EXPECT_DOUBLE_EQ(l.summary().maxMs, 50);

  // Another session's delta is not remembered: an Ack after it measures nothing.
  l.delta(8, 9, false, t0 + milliseconds(300));
  l.acked(9, t0 + milliseconds(250), 9);
  EXPECT_EQ(l.summary().samples, 4u);
  EXPECT_EQ(l.awaitingDelta(), 0u);

  // A reconnection forgets what waits, not what was measured.
  l.acked(12, t0 + milliseconds(400), 9);
  EXPECT_EQ(l.awaitingDelta(), 1u);
  l.reset();
  EXPECT_EQ(l.awaitingDelta(), 0u);
  l.delta(11, 12, true, t0 + milliseconds(500));
  EXPECT_EQ(l.summary().samples, 4u);
  EXPECT_DOUBLE_EQ(l.summary().lastMs, 10);
}

wire::Participant participant(uint64_t session, const std::string& name, wire::Role role,
                              std::vector<uint64_t> selection) {
  wire::Participant p;
  p.set_session_id(session);
  p.set_name(name);
  p.set_role(role);
  for (uint64_t id : selection) p.mutable_selection()->add_vertex_ids(id);
  return p;
}

TEST(ViewCollaborators, AFullPresenceReplacesTheListAndChangesReplaceOrRemoveEntries) {
  Collaborators c;
  const uint64_t own = 7;
  wire::Presence full;
  full.set_full(true);
  *full.add_participants() = participant(7, "bob", wire::ROLE_EDITOR, {3});
  *full.add_participants() = participant(2, "alice", wire::ROLE_VIEWER, {});
  c.apply(full, own);
  ASSERT_EQ(c.list().size(), 2u);
  EXPECT_EQ(c.list()[0].sessionId, 2u);  // in session order
  EXPECT_EQ(c.list()[0].name, "alice");
  EXPECT_EQ(c.list()[0].role, wire::ROLE_VIEWER);
  EXPECT_FALSE(c.list()[0].self);
  EXPECT_EQ(c.list()[1].name, "bob");
  EXPECT_EQ(c.list()[1].selectedVertices, std::vector<uint64_t>{3});
  EXPECT_TRUE(c.list()[1].self);

  // Changes: alice selects two vertices, carol joins, bob leaves.
  wire::Presence changes;
  *changes.add_participants() = participant(2, "alice", wire::ROLE_VIEWER, {5, 6});
  *changes.add_participants() = participant(4, "carol", wire::ROLE_EDITOR, {});
  changes.add_left_session_ids(7);
  c.apply(changes, own);
  ASSERT_EQ(c.list().size(), 2u);
  EXPECT_EQ(c.list()[0].name, "alice");
  EXPECT_EQ(c.list()[0].selectedVertices, (std::vector<uint64_t>{5, 6}));
  EXPECT_EQ(c.list()[1].sessionId, 4u);
  EXPECT_EQ(c.list()[1].name, "carol");

  // A full list of one drops everyone else.
  wire::Presence alone;
  alone.set_full(true);
  *alone.add_participants() = participant(9, "dave", wire::ROLE_EDITOR, {});
  c.apply(alone, own);
  ASSERT_EQ(c.list().size(), 1u);
  EXPECT_EQ(c.list()[0].name, "dave");
}

RegionMesh region(std::vector<Vec3> positions, std::vector<uint64_t> vertexIds) {
  RegionMesh r;
  r.positions = std::move(positions);
  r.vertexIds = std::move(vertexIds);
  return r;
}

TEST(ViewMorphKeyFollower, EachVertexGetsItsXAndYUnderEitherKey) {
  std::map<uint64_t, RegionMesh> key0, key1;
  key0[1] = region({Vec3(1, 2, 0), Vec3(3, 4, 0)}, {10, 11});
  key0[2] = region({Vec3(5, 6, 0)}, {12, 99});  // 99 has no position: left out
  key1[1] = region({Vec3(7, 8, 0), Vec3(9, 10, 0)}, {10, 13});
  const KeyPositionMap map = keyPositions(key0, key1);
  EXPECT_EQ(map.size(), 4u);
  EXPECT_EQ(map.at(10), (std::array<float, 4>{1, 2, 7, 8}));
  EXPECT_EQ(map.at(11), (std::array<float, 4>{3, 4, 0, 0}));  // not in key 1's regions
  EXPECT_EQ(map.at(12), (std::array<float, 4>{5, 6, 0, 0}));
  EXPECT_EQ(map.at(13), (std::array<float, 4>{0, 0, 9, 10}));  // not in key 0's
}

TEST(ViewMorphKeyFollower, AKeyIsFollowedUniformlyAtTheMaxLevelAtItsTime) {
  wire::LodProfile shown;
  shown.set_base_level(1);
  shown.set_max_level(4);
  shown.set_angle_threshold_degrees(15);
  shown.set_morph_t(0.4);
  const wire::LodProfile atKey = MorphKeyFollower::profileAtKey(shown, 1);
  EXPECT_EQ(atKey.base_level(), 4u);
  EXPECT_EQ(atKey.max_level(), 4u);
  EXPECT_EQ(atKey.angle_threshold_degrees(), 15);
  EXPECT_EQ(atKey.morph_t(), 1);
  EXPECT_EQ(MorphKeyFollower::profileAtKey(shown, 0).morph_t(), 0);
}

TEST(ViewUndoHistory, EditIdsCarryTheirMorphKeyThroughUndo) {
  EXPECT_EQ(keyedEditId(5, 0), 5u);
  EXPECT_EQ(keyedEditId(5, 1), 0x8000000000000005u);
  EXPECT_EQ(keyedEditId(5, 2), 5u);  // only key 1 is marked
  EXPECT_EQ(splitKeyedEditId(5).editId, 5u);
  EXPECT_EQ(splitKeyedEditId(5).key, 0u);
  EXPECT_EQ(splitKeyedEditId(0x8000000000000005u).editId, 5u);
  EXPECT_EQ(splitKeyedEditId(0x8000000000000005u).key, 1u);

  // A drag of two edits on key 1, then a key's edit on key 0.
  UndoHistory h;
  const auto drag = h.open();
  h.sent(drag);
  h.sent(drag);
  h.acked(drag, keyedEditId(3, 1));
  h.acked(drag, keyedEditId(4, 1));
  h.close(drag);
  const auto key = h.open();
  h.sent(key);
  h.close(key);
  h.acked(key, keyedEditId(4, 0));
  auto undo = h.undo();
  ASSERT_TRUE(undo.isOk());
  ASSERT_EQ(undo->size(), 1u);
  EXPECT_EQ(splitKeyedEditId((*undo)[0]).editId, 4u);
  EXPECT_EQ(splitKeyedEditId((*undo)[0]).key, 0u);
  undo = h.undo();
  ASSERT_TRUE(undo.isOk());
  ASSERT_EQ(undo->size(), 2u);  // newest first, both of key 1
  EXPECT_EQ(splitKeyedEditId((*undo)[0]).editId, 4u);
  EXPECT_EQ(splitKeyedEditId((*undo)[0]).key, 1u);
  EXPECT_EQ(splitKeyedEditId((*undo)[1]).editId, 3u);
  EXPECT_EQ(splitKeyedEditId((*undo)[1]).key, 1u);
}

}  // namespace
}  // namespace tessera::view
