// One client connection (docs/PROTOCOL.md §1-§5): frames in through a bounded
// decoder, a handshake, per-document roles from the access token, a rate
// limit, commands routed to document hosts, and a bounded outbox written
// out one frame at a time. Everything runs on the connection's strand; a
// slow client only ever fills its own outbox.
#pragma once

#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "protocol/framing.h"
#include "protocol/tessera.pb.h"
#include "server/document/subscriber.h"
#include "server/net/catalogue_commands.h"
#include "server/net/outbox.h"
#include "server/net/server_context.h"
#include "server/net/transport.h"

namespace tessera::server {

class Connection : public Subscriber, public std::enable_shared_from_this<Connection> {
 public:
  // The transport's handshake (TLS, WebSocket) runs first, inside the
  // handshake deadline. `strand` is the one the transport was made with.
  Connection(std::unique_ptr<Transport> transport, ConnectionStrand strand, ServerContext& context,
             uint64_t sessionId, std::string address);
  ~Connection() override;

  void start();
  uint64_t sessionId() const override { return sessionId_; }
  void send(Outgoing message) override;
  // Server stopping: a fatal Error, then close once it is written.
  void shutdown();
  // Refuses the connection (per-address limit) with a fatal Error.
  void refuse(wire::ErrorCode code, const std::string& message);
  const std::string& address() const { return address_; }
  // Whether the Hello carried a token some grant names; until then the
  // connection counts against the unauthenticated limits.
  bool authenticated() const { return authenticated_.load(); }
  // False once closed: a closed connection holds no slot, even while its
  // last handlers still keep the object alive.
  bool live() const { return live_.load(); }
  // Snapshot of the queue for stats: bytes, messages.
  std::pair<uint64_t, size_t> queueDepth() const { return {queueBytes_.load(), queueMessages_.load()}; }

 private:
  void readMore();
  void handle(wire::ClientMessage message);
  void handleHello(const wire::ClientMessage& message);
  // Answers a Hello whose turn has come (auth_throttle.h).
  void authenticate(const wire::ClientMessage& hello);
  // Handles the complete frames the decoder holds, then reads on, unless a
  // held Hello or the closing stops it.
  void drainFrames();
  void queue(Outgoing message);
  void reply(const wire::ServerMessage& message);
  void reject(uint64_t clientSeq, wire::RejectReason reason, const std::string& text);
  // Replies with what a command returned, counting it when it is a Reject.
  void answer(const wire::ServerMessage& message);
  // This session as the catalogue commands see it (catalogue_commands.h).
  CatalogueCaller caller();
  void fatal(wire::ErrorCode code, const std::string& message);
  void writeNext();
  void closeNow();
  void armIdleTimer(double seconds);
  void armWriteWatchdog();

  // Command handlers.
  // `cost`: the commands the message holds (an EditBatch holds several; it
  // costs at most a second's worth, so any allowed batch can pass).
  bool allowedByRate(uint64_t clientSeq, double cost = 1.0);
  std::optional<store::Role> roleFor(store::DocumentId id);
  std::shared_ptr<DocumentEndpoint> openHost(uint64_t documentId, uint64_t clientSeq);
  void createDocument(uint64_t clientSeq, const wire::CreateDocument& request);
  void openDocument(uint64_t clientSeq, uint64_t documentId);
  void closeDocument(uint64_t clientSeq, uint64_t documentId);

  std::unique_ptr<Transport> transport_;
  ConnectionStrand strand_;
  boost::asio::steady_timer idleTimer_, writeTimer_, helloTimer_;
  bool helloHeld_ = false;  // a Hello waiting for its address's turn
  std::atomic<bool> authenticated_{false};
  std::atomic<bool> live_{true};
  std::chrono::steady_clock::time_point writeStarted_;  // of the write in flight
  bool watchdogArmed_ = false;
  ServerContext& context_;
  const uint64_t sessionId_;
  const std::string address_;
  FrameDecoder decoder_;
  Outbox outbox_;
  std::atomic<uint64_t> queueBytes_{0};
  std::atomic<size_t> queueMessages_{0};

  bool helloDone_ = false, closing_ = false, closed_ = false;
  bool transportReady_ = false;  // no write may start while the transport's handshake runs
  std::string token_;            // never logged
  std::string name_;
  std::optional<store::Role> globalRole_;
  std::map<uint64_t, std::shared_ptr<DocumentEndpoint>> open_;
  std::map<uint64_t, store::Role> roles_;
  std::map<uint64_t, wire::Subscribe> subscriptions_;  // by document: what a resync asks again
  double bucket_ = 0;
  std::chrono::steady_clock::time_point refilled_;
};

}  // namespace tessera::server
