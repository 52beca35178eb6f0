// A delta's surface hash (PROTOCOL 6.5) describes the state at its
// to_version, so a merged delta carries the hash of the last delta merged.
#include <gtest/gtest.h>

#include "protocol/framing.h"
#include "protocol/tessera.pb.h"
#include "server/net/outbox.h"

namespace tessera::server {
namespace {

Outgoing deltaWithHash(uint64_t from, uint64_t to, uint64_t hash) {
  auto content = std::make_shared<DeltaContent>();
  content->documentId = 7;
  content->fromVersion = from;
  content->toVersion = to;
  content->surfaceHash = hash;
  content->regions.push_back({10 + to, std::make_shared<const std::string>("payload"), true});
  return {encodeDeltaFrame(*content, 1 << 20), content, 0};
}

std::vector<wire::Delta> queuedDeltas(Outbox& box) {
  std::vector<wire::Delta> out;
  for (const auto& frame : box.startWrite(100, 1 << 30)) {
    FrameDecoder decoder;
    EXPECT_TRUE(decoder.feed(*frame).isOk());
    wire::ServerMessage m;
    auto got = decoder.next(m);
    EXPECT_TRUE(got.isOk() && *got);
    out.push_back(m.delta());
  }
  box.finishWrite();
  return out;
}

TEST(OutboxSurfaceHash, TheFrameCarriesItAndAMergeKeepsTheLastOnes) {
  Limits limits;
  Outbox plain(limits);
  plain.push(deltaWithHash(1, 2, 0x1111), 1 << 20);
  auto one = queuedDeltas(plain);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].surface_hash(), 0x1111u);

  limits.queueSoftBytes = 1;  // every push merges
  Outbox merging(limits);
  merging.push(deltaWithHash(1, 2, 0x1111), 1 << 20);
  merging.push(deltaWithHash(2, 3, 0x2222), 1 << 20);
  merging.push(deltaWithHash(3, 4, 0x3333), 1 << 20);
  auto merged = queuedDeltas(merging);
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_EQ(merged[0].from_version(), 1u);
  EXPECT_EQ(merged[0].to_version(), 4u);
  EXPECT_EQ(merged[0].surface_hash(), 0x3333u);
}

}  // namespace
}  // namespace tessera::server
