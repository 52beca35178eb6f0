// The decoder facing hostile or broken peers: length prefixes it must refuse
// (and refuse before allocating), truncated streams, payloads that are not an
// envelope, and the sticky error state afterwards.
#include <gtest/gtest.h>

#include <google/protobuf/stubs/logging.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "protocol/framing.h"
#include "protocol/sample_messages.h"
#include "protocol/tessera.pb.h"

// "Rejected without allocation" is measured, not assumed: while a probe is
// active, this binary's global operator new records the largest request.
namespace {
std::atomic<bool> gProbeActive{false};
std::atomic<size_t> gLargestAllocation{0};
}  // namespace

void* operator new(std::size_t size) {
  if (gProbeActive.load(std::memory_order_relaxed)) {
    size_t seen = gLargestAllocation.load(std::memory_order_relaxed);
    while (size > seen && !gLargestAllocation.compare_exchange_weak(seen, size)) {
    }
  }
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// noinline: once inlined, g++ 12 sees free() meet a new-expression and warns
// (-Wmismatched-new-delete), not knowing that this operator new is malloc.
[[gnu::noinline]] void operator delete(void* p) noexcept {
  std::free(p);
}
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace tessera {
namespace {

class AllocationProbe {
 public:
  AllocationProbe() {
    gLargestAllocation = 0;
    gProbeActive = true;
  }
  ~AllocationProbe() { gProbeActive = false; }
  size_t largest() const { return gLargestAllocation.load(); }
};

std::string prefix(uint32_t length) {
  return {static_cast<char>(length >> 24), static_cast<char>(length >> 16), static_cast<char>(length >> 8),
          static_cast<char>(length)};
}

std::string framed(const std::string& payload) {
  return prefix(static_cast<uint32_t>(payload.size())) + payload;
}

std::string pingFrame() {
  wire::ClientMessage ping;
  ping.set_client_seq(7);
  ping.mutable_ping();
  return encodeFrame(ping).value();
}

bool contains(const Status& status, const std::string& text) {
  return status.message().find(text) != std::string::npos;
}

TEST(ProtocolFrameLimits, OversizedLengthIsRejectedBeforeAnyPayloadIsKept) {
  for (uint32_t announced : {1025u, 1u << 30, 0xffffffffu}) {
    FrameDecoder decoder({.maxFrameBytes = 1024});
    Status status;
    size_t largest = 0;
    {
      AllocationProbe probe;
      status = decoder.feed(prefix(announced) + std::string(64, 'x'));
      largest = probe.largest();
    }
    ASSERT_FALSE(status.isOk()) << announced;
    EXPECT_EQ(decoder.error(), FrameError::kTooLarge);
    EXPECT_TRUE(contains(status, "frame 1 (stream byte 0) announces " + std::to_string(announced) + " bytes"))
        << status.message();
    EXPECT_TRUE(contains(status, "more than the limit of 1024 bytes")) << status.message();
    EXPECT_EQ(decoder.bufferedBytes(), 0u);
    // Only the error message was allocated, never anything sized by the prefix.
    EXPECT_LT(largest, 512u) << "announced " << announced;
  }
}

// A peer may announce a large frame within the limit and then trickle: the
// decoder's memory follows the bytes that arrived, not the announced size.
TEST(ProtocolFrameLimits, AnnouncedSizeIsNotPreallocated) {
  FrameDecoder decoder({.maxFrameBytes = 1u << 30});
  size_t largest = 0;
  {
    AllocationProbe probe;
    ASSERT_TRUE(decoder.feed(prefix(512u << 20)).isOk());
    ASSERT_TRUE(decoder.feed(std::string(100, 'x')).isOk());
    largest = probe.largest();
  }
  EXPECT_EQ(decoder.bufferedBytes(), 100u);
  EXPECT_LT(largest, 4096u);
  EXPECT_EQ(decoder.finish().isOk(), false);
  EXPECT_EQ(decoder.error(), FrameError::kTruncated);
  EXPECT_TRUE(contains(decoder.status(), "got 100 of 536870912 payload bytes")) << decoder.status().message();
}

TEST(ProtocolFrameLimits, AFrameExactlyAtTheLimitIsAccepted) {
  const std::string frame = pingFrame();
  const auto length = static_cast<uint32_t>(frame.size() - kFrameHeaderBytes);
  FrameDecoder atLimit({.maxFrameBytes = length});
  ASSERT_TRUE(atLimit.feed(frame).isOk());
  wire::ClientMessage message;
  EXPECT_TRUE(atLimit.next(message).value());

  FrameDecoder belowLimit({.maxFrameBytes = length - 1});
  EXPECT_FALSE(belowLimit.feed(frame).isOk());
  EXPECT_EQ(belowLimit.error(), FrameError::kTooLarge);
}

// The first frame (a server's Hello) has its own, tighter limit; later
// frames get the full one.
TEST(ProtocolFrameLimits, TheFirstFrameHasItsOwnLimit) {
  const std::string frame = pingFrame();
  const auto length = static_cast<uint32_t>(frame.size() - kFrameHeaderBytes);
  FrameDecoder tight({.maxFrameBytes = 1u << 20, .firstFrameMaxBytes = length - 1});
  Status status = tight.feed(frame);
  ASSERT_FALSE(status.isOk());
  EXPECT_EQ(tight.error(), FrameError::kTooLarge);
  EXPECT_TRUE(
      contains(status, "more than the limit of " + std::to_string(length - 1) + " bytes for the first frame"))
      << status.message();

  FrameDecoder enough({.maxFrameBytes = 1u << 20, .firstFrameMaxBytes = length});
  ASSERT_TRUE(enough.feed(frame).isOk());
  // A second frame far above the first frame's limit is fine.
  ASSERT_TRUE(enough.feed(prefix(64u << 10) + std::string(64u << 10, 'x')).isOk());
  wire::ClientMessage message;
  EXPECT_TRUE(enough.next(message).value());
  EXPECT_EQ(enough.bufferedBytes(), 64u << 10);
}

// protobuf cannot parse more than INT_MAX bytes, so a larger limit is clamped.
TEST(ProtocolFrameLimits, LimitsAboveTwoGibibytesAreClamped) {
  FrameDecoder decoder({.maxFrameBytes = 0xffffffffu});
  Status status = decoder.feed(prefix(0x80000000u));
  ASSERT_FALSE(status.isOk());
  EXPECT_TRUE(contains(status, "more than the limit of 2147483647 bytes")) << status.message();
}

TEST(ProtocolFrameLimits, ZeroLengthIsRejected) {
  FrameDecoder decoder;
  const Status status = decoder.feed(pingFrame() + prefix(0));
  ASSERT_FALSE(status.isOk());
  EXPECT_EQ(decoder.error(), FrameError::kZeroLength);
  EXPECT_TRUE(
      contains(status, "frame 2 (stream byte " + std::to_string(pingFrame().size()) + ") announces 0 bytes"))
      << status.message();
}

TEST(ProtocolFrameLimits, TruncatedStreamsAreReportedAtTheEnd) {
  const std::string frame = pingFrame();
  for (size_t keep = 1; keep < frame.size(); ++keep) {
    FrameDecoder decoder;
    ASSERT_TRUE(decoder.feed(frame + frame.substr(0, keep)).isOk()) << keep;
    wire::ClientMessage message;
    EXPECT_TRUE(decoder.next(message).value());
    EXPECT_FALSE(decoder.next(message).value());  // nothing wrong yet: more may come
    const Status status = decoder.finish();
    ASSERT_FALSE(status.isOk()) << keep;
    EXPECT_EQ(decoder.error(), FrameError::kTruncated);
    EXPECT_TRUE(
        contains(status, "stream ended inside frame 2 (stream byte " + std::to_string(frame.size()) + ")"))
        << status.message();
    const std::string detail = keep < kFrameHeaderBytes
                                   ? "got " + std::to_string(keep) + " of 4 length-prefix bytes"
                                   : "got " + std::to_string(keep - kFrameHeaderBytes) + " of " +
                                         std::to_string(frame.size() - kFrameHeaderBytes) + " payload bytes";
    EXPECT_TRUE(contains(status, detail)) << status.message();
  }
}

TEST(ProtocolFrameLimits, CleanEndsAreNotTruncations) {
  FrameDecoder empty;
  EXPECT_TRUE(empty.finish().isOk());
  FrameDecoder whole;
  ASSERT_TRUE(whole.feed(pingFrame() + pingFrame()).isOk());
  EXPECT_TRUE(whole.finish().isOk());
  wire::ClientMessage message;
  EXPECT_TRUE(whole.next(message).value());  // complete frames still come out after the end
  EXPECT_TRUE(whole.next(message).value());
  EXPECT_FALSE(whole.next(message).value());
}

TEST(ProtocolFrameLimits, PayloadsThatAreNotAnEnvelopeAreRejected) {
  google::protobuf::LogSilencer quiet;  // protobuf logs the invalid UTF-8 case
  const std::vector<std::pair<const char*, std::string>> garbage = {
      {"unterminated varint", std::string("\xff", 1)},
      {"wire type 7", std::string("\x0f", 1)},
      {"length past the end", std::string("\x12\x10"
                                          "ab",
                                          4)},
      {"invalid nested message", std::string("\x12\x02\x0f\x00", 4)},
      {"invalid UTF-8 in a string", std::string("\x12\x03\x12\x01\xff", 5)},
      {"field number 0", std::string("\x00\x01", 2)},
  };
  for (const auto& [what, payload] : garbage) {
    FrameDecoder decoder;
    ASSERT_TRUE(decoder.feed(pingFrame() + framed(payload)).isOk()) << what;
    wire::ClientMessage message;
    EXPECT_TRUE(decoder.next(message).value()) << what;
    auto bad = decoder.next(message);
    ASSERT_FALSE(bad.isOk()) << what;
    EXPECT_EQ(decoder.error(), FrameError::kBadPayload) << what;
    EXPECT_TRUE(contains(bad.status(), "frame 2 (stream byte " + std::to_string(pingFrame().size()) +
                                           "): its " + std::to_string(payload.size()) +
                                           "-byte payload is not a valid tessera.wire.ClientMessage"))
        << what << ": " << bad.status().message();
  }
}

TEST(ProtocolFrameLimits, ErrorsAreSticky) {
  FrameDecoder decoder({.maxFrameBytes = 64});
  const Status first = decoder.feed(prefix(65));
  ASSERT_FALSE(first.isOk());
  EXPECT_EQ(decoder.feed(pingFrame()).message(), first.message());
  wire::ClientMessage message;
  for (int i = 0; i < 3; ++i) {
    auto next = decoder.next(message);
    ASSERT_FALSE(next.isOk());
    EXPECT_EQ(next.status().message(), first.message());
  }
  EXPECT_EQ(decoder.finish().message(), first.message());
  EXPECT_EQ(decoder.bufferedBytes(), 0u);
}

// Frames completed before a bad prefix still come out, then the error: the
// outcome is the same whether the bytes arrived at once or one by one.
TEST(ProtocolFrameLimits, FramesBeforeAnErrorAreDelivered) {
  const std::string stream = pingFrame() + pingFrame() + prefix(0);
  FrameDecoder decoder;
  EXPECT_FALSE(decoder.feed(stream).isOk());
  wire::ClientMessage message;
  EXPECT_TRUE(decoder.next(message).value());
  EXPECT_EQ(message.client_seq(), 7u);
  EXPECT_TRUE(decoder.next(message).value());
  auto end = decoder.next(message);
  ASSERT_FALSE(end.isOk());
  EXPECT_EQ(decoder.error(), FrameError::kZeroLength);
}

// A bad payload comes earlier in the stream than a bad prefix after it, so it
// is the error reported once the decoder has been drained.
TEST(ProtocolFrameLimits, TheFirstErrorInStreamOrderWins) {
  google::protobuf::LogSilencer quiet;
  const std::string stream = pingFrame() + framed(std::string("\x0f", 1)) + prefix(0xffffffffu);
  FrameDecoder decoder;
  EXPECT_EQ(decoder.feed(stream).isOk(), false);
  EXPECT_EQ(decoder.error(), FrameError::kTooLarge);
  wire::ClientMessage message;
  EXPECT_TRUE(decoder.next(message).value());
  EXPECT_FALSE(decoder.next(message).isOk());
  EXPECT_EQ(decoder.error(), FrameError::kBadPayload);
  EXPECT_TRUE(contains(decoder.status(), "frame 2")) << decoder.status().message();
}

}  // namespace
}  // namespace tessera
