// MessageFraming (PROTOCOL.md §1.2): one frame per binary WebSocket
// message, whatever the reads that bring it.
#include "protocol/message_framing.h"

#include <gtest/gtest.h>

#include <string>

namespace tessera {
namespace {

std::string frameOf(size_t payload) {
  std::string f(4 + payload, 'p');
  f[0] = static_cast<char>((payload >> 24) & 0xff);
  f[1] = static_cast<char>((payload >> 16) & 0xff);
  f[2] = static_cast<char>((payload >> 8) & 0xff);
  f[3] = static_cast<char>(payload & 0xff);
  return f;
}

TEST(MessageFraming, OneFramePerMessageInAnyNumberOfReads) {
  MessageFraming framing;
  const std::string f = frameOf(300);
  EXPECT_TRUE(framing.feed(f, true, true).isOk());
  // The next message in pieces of 1, 2, 3, ... bytes, the prefix split too.
  const std::string g = frameOf(1000);
  size_t at = 0;
  for (size_t n = 1; at < g.size(); ++n) {
    const size_t take = std::min(n, g.size() - at);
    const bool last = at + take == g.size();
    Status s = framing.feed(std::string_view(g).substr(at, take), last, true);
    ASSERT_TRUE(s.isOk()) << s.message();
    at += take;
  }
  EXPECT_TRUE(framing.feed(frameOf(1), true, true).isOk());
}

TEST(MessageFraming, RefusesWhatIsNotExactlyOneFrameNamingTheMessage) {
  {
    MessageFraming framing;
    ASSERT_TRUE(framing.feed(frameOf(5), true, true).isOk());
    Status s = framing.feed(frameOf(5) + frameOf(5), true, true);
    EXPECT_FALSE(s.isOk());
    EXPECT_EQ(s.message(),
              "WebSocket message 2 holds more than one frame: its prefix announces 5 payload bytes, but more "
              "follow");
  }
  {  // Too long is seen before the message ends.
    MessageFraming framing;
    Status s = framing.feed(frameOf(5) + "x", false, true);
    EXPECT_FALSE(s.isOk()) << "an extra byte passed before the message's end";
  }
  {
    MessageFraming framing;
    Status s = framing.feed(frameOf(10).substr(0, 9), true, true);
    EXPECT_EQ(s.message(),
              "WebSocket message 1 ends inside its frame: the prefix announces 10 payload bytes, the message "
              "holds 5");
  }
  {
    MessageFraming framing;
    Status s = framing.feed("ab", true, true);
    EXPECT_EQ(s.message(), "WebSocket message 1 has 2 bytes, fewer than a frame's 4-byte length prefix");
  }
  {
    MessageFraming framing;
    Status s = framing.feed(frameOf(3), true, false);
    EXPECT_EQ(s.message(), "WebSocket message 1 is text: frames travel in binary messages");
  }
}

}  // namespace
}  // namespace tessera
