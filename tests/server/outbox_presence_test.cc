// Presence is droppable from a client that falls behind (docs/PROTOCOL.md §6.3):
// above the soft limit its queued presence goes, the document is marked,
// later changes are dropped at once, and the whole list that follows the
// resync request is kept.
#include <gtest/gtest.h>

#include <string>

#include "server/net/outbox.h"

namespace tessera::server {
namespace {

Outgoing presence(uint64_t doc, bool full, size_t bytes) {
  return {.frame = std::make_shared<const std::string>(std::string(bytes, 'p')),
          .delta = nullptr,
          .snapshotOf = 0,
          .presenceOf = doc,
          .presenceFull = full};
}

Outgoing reply(size_t bytes) {
  return {.frame = std::make_shared<const std::string>(std::string(bytes, 'r')), .delta = nullptr};
}

TEST(OutboxPresence, PresenceIsDroppedAboveTheSoftLimitAndResentWhole) {
  Limits limits;
  limits.queueSoftBytes = 1000;
  limits.queueHardBytes = 100000;
  Outbox box(limits);
  box.push(presence(7, false, 300), 1 << 20);
  box.push(presence(8, false, 300), 1 << 20);
  EXPECT_EQ(box.size(), 2u);
  EXPECT_TRUE(box.takePresenceResyncs().empty());
  // A reply pushes the queue over the soft limit: both presences go, the
  // reply (never droppable) stays.
  box.push(reply(600), 1 << 20);
  EXPECT_EQ(box.size(), 1u);
  EXPECT_EQ(box.bytes(), 600u);
  // Changes for a marked document are dropped on arrival; a full list is kept.
  box.push(presence(7, false, 10), 1 << 20);
  EXPECT_EQ(box.size(), 1u);
  const auto marked = box.takePresenceResyncs();
  EXPECT_EQ(marked, (std::set<uint64_t>{7, 8}));
  box.push(presence(7, true, 50), 1 << 20);
  EXPECT_EQ(box.size(), 2u);
  EXPECT_EQ(box.drops(), 3u);
}

TEST(OutboxPresence, PresenceBeingWrittenIsNeverDropped) {
  Limits limits;
  limits.queueSoftBytes = 500;
  Outbox box(limits);
  box.push(presence(7, false, 400), 1 << 20);
  const auto writing = box.startWrite(10, 1 << 20);
  ASSERT_EQ(writing.size(), 1u);
  box.push(presence(7, false, 400), 1 << 20);  // over the soft limit now
  EXPECT_EQ(box.size(), 1u) << "the queued one goes, the one in flight stays";
  box.finishWrite();
  EXPECT_TRUE(box.empty());
  EXPECT_EQ(box.takePresenceResyncs(), (std::set<uint64_t>{7}));
}

}  // namespace
}  // namespace tessera::server
