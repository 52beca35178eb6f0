// Frames carried in WebSocket messages (PROTOCOL.md §1.2): each binary
// message is exactly one frame of §2, its 4-byte length prefix included, so
// that a WebSocket client frames like a TCP one and the server decodes both
// with the same FrameDecoder. This check keeps the rule: it sees a message's
// bytes as they arrive (a message may come in several reads) and fails as
// soon as they cannot be one frame: a text message, a message shorter than
// its prefix says, or longer. The decoder's own checks (zero length, over
// the limit) still apply to the prefix.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/util/status.h"

namespace tessera {

class MessageFraming {
 public:
  // Bytes of the current message; `last` when they end it. Messages are
  // numbered from 1 in the errors.
  Status feed(std::string_view bytes, bool last, bool binary);

 private:
  uint64_t message_ = 1;   // the current message's number
  uint64_t received_ = 0;  // its bytes so far
  unsigned char prefix_[4] = {};
  uint64_t announced_ = 0;  // prefix + payload, once the prefix is in
};

}  // namespace tessera
