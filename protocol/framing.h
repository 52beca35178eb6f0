// Length-prefixed frames: a 4-byte big-endian payload length, then that many
// bytes of one serialized envelope (ClientMessage or ServerMessage).
//
// The decoder faces untrusted peers, so it never trusts a length field: a
// prefix announcing 0 bytes or more than the configured maximum is refused as
// soon as its 4 bytes are in, before any payload is buffered. Buffering grows
// with the bytes actually received, never with the announced size, so a peer
// that announces a large frame and then trickles costs only what it sent.
//
//   FrameDecoder decoder;
//   TESSERA_RETURN_IF_ERROR(decoder.feed(bytesJustRead));
//   wire::ClientMessage message;
//   while (true) {
//     TESSERA_ASSIGN_OR_RETURN(bool got, decoder.next(message));
//     if (!got) break;
//     handle(message);
//   }
//   // at end of stream:
//   TESSERA_RETURN_IF_ERROR(decoder.finish());
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <string_view>

#include <google/protobuf/message_lite.h>

#include "core/util/status.h"

namespace tessera {

inline constexpr size_t kFrameHeaderBytes = 4;
inline constexpr uint32_t kDefaultMaxFrameBytes = 16u << 20;  // 16 MiB of payload

// Serializes `message` into one frame. Fails if its payload would be empty
// (every envelope carries a command, and peers refuse zero-length frames) or
// larger than `maxFrameBytes` (the peer would refuse it).
Expected<std::string> encodeFrame(const google::protobuf::MessageLite& message,
                                  uint32_t maxFrameBytes = kDefaultMaxFrameBytes);

struct FrameDecoderOptions {
  uint32_t maxFrameBytes = kDefaultMaxFrameBytes;  // payload bytes, prefix excluded
  // A tighter limit for the stream's first frame (0: maxFrameBytes). A
  // server's first frame is the Hello, and a peer that has not yet shown a
  // token should not make it hold megabytes (docs/PROTOCOL.md §1.1).
  uint32_t firstFrameMaxBytes = 0;
};

// Why a decoder stopped; lets a server answer with the matching wire error code.
enum class FrameError {
  kNone,
  kZeroLength,  // a prefix announced 0 bytes
  kTooLarge,    // a prefix announced more than maxFrameBytes
  kTruncated,   // the stream ended inside a frame (reported by finish())
  kBadPayload,  // a complete payload did not parse as the envelope
};

const char* frameErrorName(FrameError error);

// Memory held is at most one partial frame plus the complete frames of the
// chunks fed since next() last drained; callers bound it by reading in
// bounded chunks and draining next() after each feed().
class FrameDecoder {
 public:
  explicit FrameDecoder(FrameDecoderOptions options = {});

  // Consumes a chunk of any size (one byte is fine). Fails on a bad length
  // prefix; the failure is sticky and later bytes are ignored.
  Status feed(std::string_view bytes);

  // Parses the oldest complete frame into `message`: true if it did, false if
  // no complete frame is waiting. Frames completed before a failure are still
  // delivered, then the failure is returned from every later call. A payload
  // that does not parse precedes any failure feed() saw later in the stream,
  // so it takes that failure's place: once next() has drained, status() is the
  // first failure in stream order, whatever the chunking.
  Expected<bool> next(google::protobuf::MessageLite& message);
  // The oldest complete frame's payload, unparsed (moved out): for readers
  // that need only a few fields of most messages (the load tester's
  // counting viewers) and parse the rest themselves.
  Expected<bool> nextPayload(std::string& payload);

  // Call at end of stream: fails (kTruncated) if a frame was left unfinished.
  Status finish();

  bool failed() const { return error_ != FrameError::kNone; }
  FrameError error() const { return error_; }
  const Status& status() const { return status_; }

  // Bytes held for frames not yet returned by next(), prefixes excluded.
  size_t bufferedBytes() const;

 private:
  struct Frame {
    std::string payload;
    uint64_t number = 0;  // 1-based position in the stream, for messages
    uint64_t offset = 0;  // stream offset of its length prefix
  };

  void fail(FrameError error, Status status);
  Status headerComplete();

  FrameDecoderOptions options_;
  unsigned char header_[kFrameHeaderBytes] = {};
  size_t headerFill_ = 0;   // bytes of the current prefix received
  bool inPayload_ = false;  // the current prefix is complete and was accepted
  uint32_t payloadLength_ = 0;
  Frame current_;
  std::deque<Frame> ready_;    // complete frames, oldest first
  uint64_t streamOffset_ = 0;  // bytes consumed so far
  uint64_t framesSeen_ = 0;
  FrameError error_ = FrameError::kNone;
  Status status_;
};

}  // namespace tessera
