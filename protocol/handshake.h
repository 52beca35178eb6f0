// The version handshake: a client's first frame is a Hello carrying the
// protocol version it speaks; the server answers with a HelloAck, or with a
// fatal Error (VERSION_MISMATCH or BAD_HANDSHAKE) and closes the connection.
//
// Server side:  checkHandshake(firstMessage) -> ok, or the Status to send back
//               through makeHandshakeError(status).
// Client side:  makeHello(...) first, then checkHelloAck(firstReply).
#pragma once

#include <cstdint>
#include <string>

#include "core/util/status.h"
#include "protocol/tessera.pb.h"
#include "protocol/token_limits.h"

namespace tessera {

// Bumped on any change an old peer would misread; docs/PROTOCOL.md records the history.
inline constexpr uint32_t kProtocolVersion = 1;

// Names appear in other clients' presence lists and in server logs.
inline constexpr size_t kMaxClientNameBytes = 128;

struct HelloOptions {
  uint64_t clientSeq = 1;
  std::string clientName = {};
  std::string token = {};
  uint32_t protocolVersion = kProtocolVersion;  // tests set others to exercise mismatches
};

struct HelloAckOptions {
  uint64_t clientSeq = 0;  // the Hello's
  std::string serverVersion = {};
  uint64_t sessionId = 0;
  wire::Role role = wire::ROLE_UNSPECIFIED;
  uint32_t maxFrameBytes = 0;
};

wire::ClientMessage makeHello(const HelloOptions& options);
wire::ServerMessage makeHelloAck(const HelloAckOptions& options);

// Checks a Hello against the server's version and the field limits.
// A version mismatch is kUnsupported ("client speaks protocol 2, server
// speaks 1"); a malformed field is kInvalidArgument.
Status checkHello(const wire::Hello& hello, uint32_t serverVersion = kProtocolVersion);

// As checkHello, and first that the message is a Hello at all.
Status checkHandshake(const wire::ClientMessage& first, uint32_t serverVersion = kProtocolVersion);

// The fatal Error a server sends for a failed checkHandshake().
wire::ServerMessage makeHandshakeError(const Status& status);

// Client side: the server's first reply must be a HelloAck of our version;
// an Error is turned into a Status carrying the server's message.
Status checkHelloAck(const wire::ServerMessage& first, uint32_t clientVersion = kProtocolVersion);

}  // namespace tessera
