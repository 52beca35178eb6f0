// The frame decoder (protocol/framing.h) on an untrusted byte stream.
//
// Input: byte 0 picks the chunk size (1..32 bytes per feed()) and whether
// envelopes are read as ClientMessage or ServerMessage; byte 1 picks a small
// maxFrameBytes (so the size limit is reachable); the rest is the stream.
// Besides the sanitizers, the decoder's documented promises are checked:
// feeding in chunks (draining after each) and feeding at once deliver the
// same frames and end in the same error, whatever the chunking; failures are
// sticky; buffering never exceeds what was fed; every delivered envelope
// re-encodes into a frame that decodes to the same message.
#include <algorithm>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "protocol/framing.h"
#include "protocol/tessera.pb.h"

namespace tessera::fuzz {
namespace {

struct Outcome {
  std::vector<std::string> messages;  // serialized as delivered
  FrameError error = FrameError::kNone;
};

template <typename Message>
void drain(FrameDecoder& decoder, Outcome& out) {
  Message message;
  while (true) {
    auto got = decoder.next(message);
    if (!got.isOk()) {
      checkError(got.status(), "FrameDecoder::next");
      require(decoder.failed(), "next() failed but failed() is false");
      return;
    }
    if (!*got) return;
    out.messages.push_back(message.SerializeAsString());
  }
}

template <typename Message>
Outcome decode(std::string_view stream, size_t chunk, uint32_t maxFrameBytes) {
  FrameDecoder decoder({.maxFrameBytes = maxFrameBytes});
  Outcome out;
  size_t fed = 0;
  for (size_t at = 0; at < stream.size(); at += chunk) {
    const std::string_view piece = stream.substr(at, chunk);
    const bool wasFailed = decoder.failed();
    Status status = decoder.feed(piece);
    fed += piece.size();
    checkError(status, "FrameDecoder::feed");
    if (wasFailed) require(!status.isOk(), "a failure was not sticky");
    require(decoder.bufferedBytes() <= fed, "buffered more bytes than were fed");
    drain<Message>(decoder, out);
  }
  Status finished = decoder.finish();
  checkError(finished, "FrameDecoder::finish");
  drain<Message>(decoder, out);
  out.error = decoder.error();
  return out;
}

template <typename Message>
void run(std::string_view stream, size_t chunk, uint32_t maxFrameBytes) {
  const Outcome chunked = decode<Message>(stream, chunk, maxFrameBytes);
  const Outcome whole = decode<Message>(stream, std::max<size_t>(stream.size(), 1), maxFrameBytes);
  require(chunked.messages == whole.messages, "chunking changed the frames delivered");
  require(chunked.error == whole.error, std::string("chunking changed the error: ") +
                                            frameErrorName(chunked.error) + " vs " +
                                            frameErrorName(whole.error));
  for (const std::string& bytes : whole.messages) {
    Message message;
    require(message.ParseFromString(bytes), "a delivered message does not re-parse");
    if (message.ByteSizeLong() == 0) continue;  // an all-default envelope: encodeFrame refuses empty payloads
    auto frame = encodeFrame(message, 1u << 20);
    if (!frame.isOk()) {
      checkError(frame.status(), "encodeFrame");
      continue;
    }
    Outcome again = decode<Message>(*frame, frame->size(), 1u << 20);
    require(again.messages.size() == 1 && again.error == FrameError::kNone,
            "a re-encoded frame does not decode");
    require(again.messages[0] == message.SerializeAsString(),
            "a re-encoded frame decodes to another message");
  }
}

}  // namespace
}  // namespace tessera::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  if (size < 2) return 0;
  const size_t chunk = 1 + (data[0] & 31);
  const bool server = (data[0] & 32) != 0;
  // 16 bytes .. 64 KiB: small enough that kTooLarge is found, large enough for real envelopes.
  const uint32_t maxFrameBytes = 16u << (data[1] % 13);
  const std::string_view stream(reinterpret_cast<const char*>(data + 2), size - 2);
  if (server) {
    fuzz::run<wire::ServerMessage>(stream, chunk, maxFrameBytes);
  } else {
    fuzz::run<wire::ClientMessage>(stream, chunk, maxFrameBytes);
  }
  return 0;
}
