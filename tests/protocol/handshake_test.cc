// The version handshake, from both ends, including through real frames.
#include <gtest/gtest.h>

#include "protocol/framing.h"
#include "protocol/handshake.h"

namespace tessera {
namespace {

TEST(ProtocolHandshake, MatchingVersionIsAccepted) {
  const auto hello = makeHello({.clientSeq = 1, .clientName = "alice", .token = "t0k"});
  EXPECT_EQ(hello.hello().protocol_version(), kProtocolVersion);
  EXPECT_TRUE(checkHandshake(hello).isOk());
}

TEST(ProtocolHandshake, VersionMismatchNamesBothVersions) {
  const auto hello = makeHello({.clientName = "future", .protocolVersion = 2});
  const Status status = checkHandshake(hello);
  ASSERT_FALSE(status.isOk());
  EXPECT_EQ(status.code(), ErrorCode::kUnsupported);
  EXPECT_EQ(status.message(), "client speaks protocol 2, server speaks 1");

  const auto error = makeHandshakeError(status);
  ASSERT_TRUE(error.has_error());
  EXPECT_EQ(error.error().code(), wire::ERROR_CODE_VERSION_MISMATCH);
  EXPECT_TRUE(error.error().fatal());
  EXPECT_EQ(error.error().message(), "client speaks protocol 2, server speaks 1");

  // A server of a later version names its own.
  EXPECT_EQ(checkHandshake(makeHello({}), 3).message(), "client speaks protocol 1, server speaks 3");
}

TEST(ProtocolHandshake, MissingVersionIsAMismatch) {
  const Status status = checkHandshake(makeHello({.protocolVersion = 0}));
  ASSERT_FALSE(status.isOk());
  EXPECT_EQ(status.code(), ErrorCode::kUnsupported);
  EXPECT_EQ(status.message(), "the Hello carries no protocol_version; server speaks protocol 1");
}

TEST(ProtocolHandshake, FirstFrameMustBeAHello) {
  wire::ClientMessage ping;
  ping.mutable_ping();
  Status status = checkHandshake(ping);
  ASSERT_FALSE(status.isOk());
  EXPECT_EQ(status.message(), "the first frame must be a Hello, got ping");
  EXPECT_EQ(makeHandshakeError(status).error().code(), wire::ERROR_CODE_BAD_HANDSHAKE);

  status = checkHandshake(wire::ClientMessage());
  EXPECT_EQ(status.message(), "the first frame must be a Hello, got an envelope with nothing set");
}

TEST(ProtocolHandshake, HelloFieldsAreBounded) {
  Status status = checkHandshake(makeHello({.clientName = std::string(kMaxClientNameBytes + 1, 'n')}));
  EXPECT_EQ(status.message(), "Hello.client_name is 129 bytes, more than the limit of 128");
  EXPECT_TRUE(checkHandshake(makeHello({.clientName = std::string(kMaxClientNameBytes, 'n')})).isOk());

  status = checkHandshake(makeHello({.clientName = "eve\n[admin] logged in"}));
  EXPECT_EQ(status.message(), "Hello.client_name contains control character 0x0a at byte 3");
  EXPECT_TRUE(checkHandshake(makeHello({.clientName = "Zoë 🙂"})).isOk());

  // The token's length is checked but its content never appears in a message.
  status = checkHandshake(makeHello({.token = std::string(kMaxTokenBytes + 1, 's')}));
  EXPECT_EQ(status.message(), "Hello.token is 4097 bytes, more than the limit of 4096");
}

TEST(ProtocolHandshake, ClientChecksTheServersReply) {
  const auto ack = makeHelloAck(
      {.clientSeq = 1, .serverVersion = "tessera-server 0.1.0", .sessionId = 9, .role = wire::ROLE_VIEWER});
  EXPECT_EQ(ack.hello_ack().protocol_version(), kProtocolVersion);
  EXPECT_TRUE(checkHelloAck(ack).isOk());
  EXPECT_EQ(checkHelloAck(ack, 2).message(), "server speaks protocol 1, client speaks 2");

  const auto refusal = makeHandshakeError(unsupported("client speaks protocol 2, server speaks 1"));
  const Status status = checkHelloAck(refusal);
  EXPECT_EQ(status.code(), ErrorCode::kUnsupported);
  EXPECT_EQ(status.message(),
            "server refused the handshake (ERROR_CODE_VERSION_MISMATCH): client speaks protocol 2, server "
            "speaks 1");

  wire::ServerMessage newer;
  newer.mutable_error()->set_code(static_cast<wire::ErrorCode>(99));
  newer.mutable_error()->set_message("from the future");
  EXPECT_EQ(checkHelloAck(newer).message(), "server refused the handshake (error code 99): from the future");

  wire::ServerMessage pong;
  pong.mutable_pong();
  EXPECT_EQ(checkHelloAck(pong).message(), "the server's first frame must be a HelloAck, got pong");
}

// The whole exchange through frames, as the server and client will do it.
TEST(ProtocolHandshake, MismatchThroughFrames) {
  auto helloFrame = encodeFrame(makeHello({.clientName = "old client", .protocolVersion = 2}));
  ASSERT_TRUE(helloFrame.isOk());
  FrameDecoder serverSide;
  ASSERT_TRUE(serverSide.feed(*helloFrame).isOk());
  wire::ClientMessage first;
  ASSERT_TRUE(serverSide.next(first).value());
  const Status verdict = checkHandshake(first);
  ASSERT_FALSE(verdict.isOk());

  auto replyFrame = encodeFrame(makeHandshakeError(verdict));
  ASSERT_TRUE(replyFrame.isOk());
  FrameDecoder clientSide;
  ASSERT_TRUE(clientSide.feed(*replyFrame).isOk());
  wire::ServerMessage reply;
  ASSERT_TRUE(clientSide.next(reply).value());
  EXPECT_EQ(checkHelloAck(reply).message(),
            "server refused the handshake (ERROR_CODE_VERSION_MISMATCH): client speaks protocol 2, server "
            "speaks 1");
}

}  // namespace
}  // namespace tessera
