// A slow client's queued deltas merge (server/outbox.h): the newest payload
// per region, except that a moved region's payload, which leaves its ids to
// the layout the receiver holds, must stay behind the self-contained
// payload that brought that layout -- the merged delta applies in order.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "protocol/framing.h"
#include "protocol/tessera.pb.h"
#include "server/net/outbox.h"

namespace tessera::server {
namespace {

std::shared_ptr<const std::string> bytesOf(const std::string& text) {
  return std::make_shared<const std::string>(text);
}

Outgoing deltaOf(uint64_t from, uint64_t to, std::vector<RegionPayload> regions,
                 std::vector<uint64_t> removed = {}) {
  auto content = std::make_shared<DeltaContent>();
  content->documentId = 7;
  content->fromVersion = from;
  content->toVersion = to;
  content->regions = std::move(regions);
  content->removed = std::move(removed);
  return {encodeDeltaFrame(*content, 1 << 20), content, 0};
}

// The (region, payload) pairs of each queued delta, in order.
std::vector<std::vector<std::pair<uint64_t, std::string>>> queued(Outbox& box) {
  std::vector<std::vector<std::pair<uint64_t, std::string>>> out;
  for (const auto& frame : box.startWrite(100, 1 << 30)) {
    FrameDecoder decoder;
    EXPECT_TRUE(decoder.feed(*frame).isOk());
    wire::ServerMessage m;
    auto got = decoder.next(m);
    EXPECT_TRUE(got.isOk() && *got);
    out.emplace_back();
    for (const auto& r : m.delta().regions()) out.back().emplace_back(r.region_id(), r.draco());
  }
  box.finishWrite();
  return out;
}

TEST(OutboxMerge, AMovedRegionStaysBehindThePayloadThatBroughtItsLayout) {
  Limits limits;
  limits.queueSoftBytes = 1;  // every push merges
  Outbox box(limits);
  box.push(deltaOf(1, 2, {{10, bytesOf("A2 full"), true}, {11, bytesOf("B2 moved"), false}}), 1 << 20);
  box.push(deltaOf(2, 3, {{10, bytesOf("A3 moved"), false}, {11, bytesOf("B3 moved"), false}}), 1 << 20);
  box.push(deltaOf(3, 4, {{10, bytesOf("A4 moved"), false}, {12, bytesOf("C4 full"), true}}), 1 << 20);
  const auto deltas = queued(box);
  ASSERT_EQ(deltas.size(), 1u);
  const std::vector<std::pair<uint64_t, std::string>> expected = {
      {10, "A2 full"}, {11, "B3 moved"}, {10, "A4 moved"}, {12, "C4 full"}};
  EXPECT_EQ(deltas[0], expected);
  EXPECT_EQ(box.merges(), 2u);
}

TEST(OutboxMerge, ASelfContainedPayloadReplacesEverythingBeforeIt) {
  Limits limits;
  limits.queueSoftBytes = 1;
  Outbox box(limits);
  box.push(deltaOf(1, 2, {{10, bytesOf("A2 full"), true}}), 1 << 20);
  box.push(deltaOf(2, 3, {{10, bytesOf("A3 moved"), false}}), 1 << 20);
  box.push(deltaOf(3, 4, {{10, bytesOf("A4 full"), true}, {11, bytesOf("B4 full"), true}}), 1 << 20);
  box.push(deltaOf(4, 5, {}, {11}), 1 << 20);
  const auto deltas = queued(box);
  ASSERT_EQ(deltas.size(), 1u);
  const std::vector<std::pair<uint64_t, std::string>> expected = {{10, "A4 full"}};
  EXPECT_EQ(deltas[0], expected);
}

}  // namespace
}  // namespace tessera::server
