// peekDelta (the load tester's counting viewers): the versions it reads
// without parsing equal a full parse's, and anything that is not a
// well-formed Delta envelope is left to the full parser.
#include <gtest/gtest.h>

#include "client/replay/delta_peek.h"
#include "protocol/tessera.pb.h"

namespace tessera::replay {
namespace {

std::string deltaPayload(uint64_t document, uint64_t from, uint64_t to) {
  wire::ServerMessage m;
  wire::Delta* d = m.mutable_delta();
  d->set_document_id(document);
  d->set_from_version(from);
  d->set_to_version(to);
  for (uint64_t r = 0; r < 3; ++r) {
    wire::Region* region = d->add_regions();
    region->set_region_id(r << 58 | 7);
    region->set_draco(std::string(1000 + r, static_cast<char>('a' + r)));
  }
  d->add_removed_region_ids(99);
  d->set_author_session_id(12);
  d->set_edit_id(uint64_t{1} << 40);
  return m.SerializeAsString();
}

TEST(DeltaPeek, ReadsTheVersionsAFullParseReads) {
  for (auto [doc, from, to] :
       {std::tuple<uint64_t, uint64_t, uint64_t>{1, 1, 2}, {7, 300, 304}, {1ull << 50, 0, 1}}) {
    const std::string payload = deltaPayload(doc, from, to);
    auto h = peekDelta(payload);
    ASSERT_TRUE(h.has_value());
    wire::ServerMessage parsed;
    ASSERT_TRUE(parsed.ParseFromString(payload));
    EXPECT_EQ(h->documentId, parsed.delta().document_id());
    EXPECT_EQ(h->fromVersion, parsed.delta().from_version());
    EXPECT_EQ(h->toVersion, parsed.delta().to_version());
  }
}

TEST(DeltaPeek, OtherMessagesAndMalformedBytesAreLeftToTheParser) {
  wire::ServerMessage presence;
  presence.mutable_presence()->set_document_id(1);
  EXPECT_FALSE(peekDelta(presence.SerializeAsString()).has_value());
  wire::ServerMessage snapshot;
  snapshot.mutable_snapshot()->set_version(3);
  EXPECT_FALSE(peekDelta(snapshot.SerializeAsString()).has_value());
  EXPECT_FALSE(peekDelta("").has_value());
  const std::string payload = deltaPayload(1, 4, 5);
  for (size_t cut : {size_t{1}, size_t{2}, size_t{10}, payload.size() / 2, payload.size() - 1}) {
    EXPECT_FALSE(peekDelta(std::string_view(payload).substr(0, cut)).has_value()) << cut;
  }
  EXPECT_FALSE(peekDelta(payload + "\x08\x01").has_value());  // a second body field after the delta
}

}  // namespace
}  // namespace tessera::replay
