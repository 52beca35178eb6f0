// A client's connection to tessera-server (docs/PROTOCOL.md): TCP, the version
// handshake, and frames in and out through the bounds-checked decoder.
// Blocking calls with deadlines, so the viewer, the replay client, the CLI
// and tests drive it from their own threads.
//
//   auto s = Session::connect({.port = 7878, .name = "alice", .token = t});
//   auto reply = (*s)->call(openDocument(3));      // waits for its Ack/Reject
//   auto next = (*s)->receive(1.0);                  // deltas, presence, ...
#pragma once

#include <array>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl.hpp>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "core/util/status.h"
#include "protocol/commands.h"
#include "protocol/framing.h"
#include "protocol/tessera.pb.h"

namespace tessera::client {

struct SessionOptions {
  std::string host = "127.0.0.1";
  uint16_t port = 7878;
  std::string name = "tessera-client";
  std::string token = {};
  double timeoutSeconds = 10;
  uint32_t maxFrameBytes = 64u << 20;
  int receiveBufferBytes = 0;     // SO_RCVBUF; 0 keeps the system's (tests shrink it to act slow)
  std::string localAddress = {};  // bind to this source address first (tests: other loopback addresses)
  bool tls = false;               // TLS, verifying the server's certificate and host name
  std::string tlsCaFile = {};     // trusted certificates (PEM); empty: the system's
};

class Session {
 public:
  static Expected<std::unique_ptr<Session>> connect(const SessionOptions& options);
  // The same; when the server refuses the handshake with an Error (an unknown
  // token: ERROR_CODE_AUTH_FAILED, ...), its code is stored in `*refusal`
  // (left alone otherwise), so a caller can explain it without parsing text.
  static Expected<std::unique_ptr<Session>> connect(const SessionOptions& options, wire::ErrorCode* refusal);
  // connect(), retried with exponential backoff (delay doubling from
  // `firstDelaySeconds`, at most 5 s apart) until it succeeds or `attempts`
  // are spent; the last error is returned.
  static Expected<std::unique_ptr<Session>> connectWithBackoff(const SessionOptions& options, int attempts,
                                                               double firstDelaySeconds = 0.1);

  uint64_t sessionId() const { return sessionId_; }
  wire::Role role() const { return role_; }

  // Sends a message; a zero client_seq gets the next one. Returns the seq.
  Expected<uint64_t> send(wire::ClientMessage message);
  // The next server message, or an error after `timeoutSeconds`, on a
  // closed connection, or on a malformed frame.
  Expected<wire::ServerMessage> receive(double timeoutSeconds);
  // Sends and waits for the reply to it (Ack, Reject, DocumentList, Pong,
  // StatsReply, ExportResult); other messages meanwhile are kept, in order,
  // for receive().
  Expected<wire::ServerMessage> call(wire::ClientMessage message, double timeoutSeconds);
  // Raw bytes, for tests of the server's frame checks.
  Status sendRaw(const std::string& bytes);
  void close();

 private:
  Session(const SessionOptions& options);
  Expected<wire::ServerMessage> readMessage(double timeoutSeconds);
  void startRead();

  // The read in flight into buffer_, if any; it survives a receive timeout.
  struct PendingRead {
    bool pending = false;
    boost::system::error_code result = {};
    size_t bytes = 0;
  };

  SessionOptions options_;
  boost::asio::io_context io_;
  boost::asio::ip::tcp::socket socket_;
  std::unique_ptr<boost::asio::ssl::context> tlsContext_;
  std::optional<boost::asio::ssl::stream<boost::asio::ip::tcp::socket&>> tls_;
  FrameDecoder decoder_;
  std::array<char, 64 * 1024> buffer_{};
  PendingRead read_;
  std::deque<wire::ServerMessage> backlog_;
  uint64_t nextSeq_ = 1;
  uint64_t sessionId_ = 0;
  wire::Role role_ = wire::ROLE_UNSPECIFIED;
};

// The client_seq a server message answers, or 0 for unsolicited ones.
using tessera::replyTo;  // protocol/commands.h
// Whether receive() failed only because nothing arrived in time (the
// connection is still usable).
bool isReceiveTimeout(const Status& status);

}  // namespace tessera::client
