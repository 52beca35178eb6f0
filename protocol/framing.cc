#include "protocol/framing.h"

#include <algorithm>
#include <climits>
#include <utility>

#include "core/util/byte_io.h"

namespace tessera {

namespace {

// protobuf's C++ runtime parses and serializes at most INT_MAX bytes at once.
constexpr uint64_t kProtobufMaxBytes = INT_MAX;

std::string describeFrame(uint64_t number, uint64_t offset) {
  return "frame " + std::to_string(number) + " (stream byte " + std::to_string(offset) + ")";
}

}  // namespace

Expected<std::string> encodeFrame(const google::protobuf::MessageLite& message, uint32_t maxFrameBytes) {
  const size_t size = message.ByteSizeLong();
  if (size == 0) {
    return invalidArgument("cannot frame an empty " + message.GetTypeName() +
                           ": zero-length frames are invalid, set its command");
  }
  const uint64_t limit = std::min<uint64_t>(maxFrameBytes, kProtobufMaxBytes);
  if (size > limit) {
    return invalidArgument(message.GetTypeName() + " of " + std::to_string(size) +
                           " bytes exceeds the frame limit of " + std::to_string(limit) + " bytes");
  }
  std::string frame(kFrameHeaderBytes + size, '\0');
  putBigEndian32(static_cast<uint32_t>(size), frame.data());  // size <= limit < 2^32
  if (!message.SerializeToArray(frame.data() + kFrameHeaderBytes, static_cast<int>(size))) {
    return internalError("serializing a " + message.GetTypeName() + " of " + std::to_string(size) +
                         " bytes failed");
  }
  return frame;
}

const char* frameErrorName(FrameError error) {
  switch (error) {
    case FrameError::kNone:
      return "none";
    case FrameError::kZeroLength:
      return "zero-length frame";
    case FrameError::kTooLarge:
      return "frame too large";
    case FrameError::kTruncated:
      return "truncated frame";
    case FrameError::kBadPayload:
      return "bad payload";
  }
  return "unknown frame error";
}

FrameDecoder::FrameDecoder(FrameDecoderOptions options) : options_(options) {
  options_.maxFrameBytes =
      static_cast<uint32_t>(std::min<uint64_t>(options_.maxFrameBytes, kProtobufMaxBytes));
}

Status FrameDecoder::feed(std::string_view bytes) {
  if (failed()) return status_;
  size_t pos = 0;
  while (pos < bytes.size()) {
    if (!inPayload_) {
      if (headerFill_ == 0) {
        current_.number = ++framesSeen_;
        current_.offset = streamOffset_;
      }
      const size_t take = std::min(kFrameHeaderBytes - headerFill_, bytes.size() - pos);
      std::copy_n(bytes.data() + pos, take, header_ + headerFill_);
      headerFill_ += take;
      pos += take;
      streamOffset_ += take;
      if (headerFill_ < kFrameHeaderBytes) break;
      // The length is judged here, before a single payload byte is kept.
      TESSERA_RETURN_IF_ERROR(headerComplete());
      continue;
    }
    // Append only what arrived: a peer announcing a large frame and sending
    // little costs little.
    const size_t take = std::min<size_t>(payloadLength_ - current_.payload.size(), bytes.size() - pos);
    current_.payload.append(bytes.data() + pos, take);
    pos += take;
    streamOffset_ += take;
    if (current_.payload.size() == payloadLength_) {
      ready_.push_back(std::move(current_));
      current_ = Frame{};
      headerFill_ = 0;
      inPayload_ = false;
    }
  }
  return Status::ok();
}

Status FrameDecoder::headerComplete() {
  const uint32_t length = getBigEndian32(header_);
  const std::string where = describeFrame(current_.number, current_.offset);
  if (length == 0) {
    fail(FrameError::kZeroLength,
         parseError(where +
                    " announces 0 bytes: an empty frame is invalid (every envelope carries a command)"));
    return status_;
  }
  const bool first = current_.number == 1 && options_.firstFrameMaxBytes > 0;
  const uint32_t limit =
      first ? std::min(options_.firstFrameMaxBytes, options_.maxFrameBytes) : options_.maxFrameBytes;
  if (length > limit) {
    fail(FrameError::kTooLarge,
         parseError(where + " announces " + std::to_string(length) + " bytes, more than the limit of " +
                    std::to_string(limit) + " bytes" + (first ? " for the first frame (the Hello)" : "")));
    return status_;
  }
  payloadLength_ = length;
  inPayload_ = true;
  return Status::ok();
}

Expected<bool> FrameDecoder::next(google::protobuf::MessageLite& message) {
  if (ready_.empty()) {
    if (failed()) return status_;
    return false;
  }
  Frame frame = std::move(ready_.front());
  ready_.pop_front();
  if (!message.ParseFromString(frame.payload)) {
    message.Clear();
    // This frame precedes anything feed() rejected, so its error wins.
    fail(FrameError::kBadPayload, parseError(describeFrame(frame.number, frame.offset) + ": its " +
                                             std::to_string(frame.payload.size()) +
                                             "-byte payload is not a valid " + message.GetTypeName()));
    ready_.clear();
    return status_;
  }
  return true;
}

Expected<bool> FrameDecoder::nextPayload(std::string& payload) {
  if (ready_.empty()) {
    if (failed()) return status_;
    return false;
  }
  payload = std::move(ready_.front().payload);
  ready_.pop_front();
  return true;
}

Status FrameDecoder::finish() {
  if (failed() || headerFill_ == 0) return status_;
  const std::string where = "stream ended inside " + describeFrame(current_.number, current_.offset);
  if (!inPayload_) {
    fail(FrameError::kTruncated, parseError(where + ": got " + std::to_string(headerFill_) + " of " +
                                            std::to_string(kFrameHeaderBytes) + " length-prefix bytes"));
  } else {
    fail(FrameError::kTruncated, parseError(where + ": got " + std::to_string(current_.payload.size()) +
                                            " of " + std::to_string(payloadLength_) + " payload bytes"));
  }
  return status_;
}

size_t FrameDecoder::bufferedBytes() const {
  size_t total = current_.payload.size();
  for (const Frame& frame : ready_) total += frame.payload.size();
  return total;
}

void FrameDecoder::fail(FrameError error, Status status) {
  error_ = error;
  status_ = std::move(status);
  current_.payload = std::string();  // release the partial payload's memory
  inPayload_ = false;
}

}  // namespace tessera
