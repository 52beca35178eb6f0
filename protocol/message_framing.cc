#include "protocol/message_framing.h"

#include <string>

#include "core/util/byte_io.h"
#include "protocol/framing.h"

namespace tessera {

Status MessageFraming::feed(std::string_view bytes, bool last, bool binary) {
  const std::string where = "WebSocket message " + std::to_string(message_);
  if (!binary) return invalidArgument(where + " is text: frames travel in binary messages");
  for (size_t i = 0; i < bytes.size() && received_ + i < kFrameHeaderBytes; ++i) {
    prefix_[received_ + i] = static_cast<unsigned char>(bytes[i]);
  }
  received_ += bytes.size();
  if (announced_ == 0 && received_ >= kFrameHeaderBytes) {
    const uint64_t payload = getBigEndian32(prefix_);
    announced_ = kFrameHeaderBytes + payload;
  }
  if (announced_ != 0 && received_ > announced_) {
    return invalidArgument(where + " holds more than one frame: its prefix announces " +
                           std::to_string(announced_ - kFrameHeaderBytes) +
                           " payload bytes, but more follow");
  }
  if (!last) return Status::ok();
  if (received_ < kFrameHeaderBytes) {
    return invalidArgument(where + " has " + std::to_string(received_) +
                           " bytes, fewer than a frame's 4-byte length prefix");
  }
  if (received_ < announced_) {
    return invalidArgument(where + " ends inside its frame: the prefix announces " +
                           std::to_string(announced_ - kFrameHeaderBytes) +
                           " payload bytes, the message holds " +
                           std::to_string(received_ - kFrameHeaderBytes));
  }
  ++message_;
  received_ = 0;
  announced_ = 0;
  return Status::ok();
}

}  // namespace tessera
