#include "server/net/connection.h"

#include <malloc.h>
#include <unistd.h>
#include <boost/asio/bind_executor.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/write.hpp>
#include <filesystem>
#include <fstream>

#include "core/document/document_file.h"
#include "protocol/commands.h"
#include "protocol/handshake.h"
#include "server/base/log.h"
#include "server/document/document_dispatch.h"
#include "server/document/journal_entry.h"
#include "server/document/mesh_intake.h"
#include "server/document/profile_request.h"
#include "server/document/replies.h"
#include "server/net/catalogue_commands.h"

namespace tessera::server {

namespace asio = boost::asio;

namespace {

constexpr const char* kServerVersion = "tessera-server 0.1.0";

wire::Role wireRole(store::Role role) {
  switch (role) {
    case store::Role::kViewer:
      return wire::ROLE_VIEWER;
    case store::Role::kEditor:
      return wire::ROLE_EDITOR;
    case store::Role::kAdmin:
      return wire::ROLE_ADMIN;
  }
  return wire::ROLE_UNSPECIFIED;
}

}  // namespace

Connection::Connection(std::unique_ptr<Transport> transport, ConnectionStrand strand, ServerContext& context,
                       uint64_t sessionId, std::string address)
    : transport_(std::move(transport)),
      strand_(std::move(strand)),
      idleTimer_(strand_),
      writeTimer_(strand_),
      helloTimer_(strand_),
      context_(context),
      sessionId_(sessionId),
      address_(std::move(address)),
      decoder_(FrameDecoderOptions{context.config.limits.maxFrameBytes, context.config.limits.helloMaxBytes}),
      outbox_(context.config.limits),
      bucket_(context.config.limits.commandsPerSecond),
      refilled_(std::chrono::steady_clock::now()) {
  transportReady_ = !transport_->needsHandshake();
  ++context_.stats.connections;
  ++context_.stats.connectionsTotal;
}

Connection::~Connection() {
  --context_.stats.connections;
}

void Connection::start() {
  asio::post(strand_, [self = shared_from_this()] {
    logEvent(LogLevel::kInfo, "connected",
             {{"session", self->sessionId_},
              {"address", self->address_},
              {"transport", self->transport_->kind()}});
    self->armIdleTimer(self->context_.config.timeouts.handshakeSeconds);
    if (self->transportReady_) return self->readMore();
    self->transport_->start([self](const boost::system::error_code& ec) {
      if (self->closed_) return;
      if (ec) {
        logEvent(LogLevel::kInfo, "transport_handshake_failed",
                 {{"session", self->sessionId_},
                  {"transport", self->transport_->kind()},
                  {"error", ec.message()}});
        return self->closeNow();
      }
      self->transportReady_ = true;
      self->readMore();
      self->writeNext();
    });
  });
}

void Connection::armIdleTimer(double seconds) {
  idleTimer_.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(seconds)));
  idleTimer_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
    if (ec || self->closed_) return;
    self->fatal(wire::ERROR_CODE_TIMEOUT, self->helloDone_ ? "idle timeout" : "no Hello in time");
  });
}

void Connection::readMore() {
  if (closed_ || closing_) return;
  transport_->read([self = shared_from_this()](const boost::system::error_code& ec, std::string_view bytes,
                                               Status framing) {
    if (self->closed_) return;
    if (ec) {
      if (ec != asio::error::eof && ec != asio::error::operation_aborted) {
        logEvent(LogLevel::kDebug, "read_failed", {{"session", self->sessionId_}, {"error", ec.message()}});
      }
      self->closeNow();
      return;
    }
    // A WebSocket message that is not exactly one frame is refused whole.
    // A prefix the decoder refuses (too large, zero) is the more precise
    // error, so the decoder sees the bytes first; none of the message's
    // frames is handled.
    if (!framing.isOk()) {
      if (!bytes.empty()) (void)self->decoder_.feed(bytes);
      if (self->decoder_.failed()) {
        return self->fatal(self->decoder_.error() == FrameError::kTooLarge ? wire::ERROR_CODE_FRAME_TOO_LARGE
                                                                           : wire::ERROR_CODE_MALFORMED_FRAME,
                           self->decoder_.status().message());
      }
      return self->fatal(wire::ERROR_CODE_MALFORMED_FRAME, framing.message());
    }
    // Bytes extend the idle deadline only after the Hello: the handshake
    // deadline is absolute, so a peer trickling a byte at a time cannot
    // hold an unauthenticated slot.
    if (self->helloDone_) self->armIdleTimer(self->context_.config.timeouts.idleSeconds);
    // A failed feed is sticky and reported by next() once the frames
    // before it are handled.
    (void)self->decoder_.feed(bytes);
    self->drainFrames();
  });
}

void Connection::drainFrames() {
  while (!closing_ && !helloHeld_) {
    wire::ClientMessage message;
    auto got = decoder_.next(message);
    if (!got.isOk()) {
      const FrameError kind = decoder_.error();
      fatal(
          kind == FrameError::kTooLarge ? wire::ERROR_CODE_FRAME_TOO_LARGE : wire::ERROR_CODE_MALFORMED_FRAME,
          got.status().message());
      return;
    }
    if (!*got) break;
    handle(std::move(message));
  }
  if (!helloHeld_) readMore();
}

void Connection::send(Outgoing message) {
  asio::post(strand_, [self = shared_from_this(), message = std::move(message)]() mutable {
    self->queue(std::move(message));
  });
}

void Connection::queue(Outgoing message) {
  if (closed_ || !message.frame) return;
  const uint64_t merges = outbox_.merges();
  outbox_.push(std::move(message), context_.config.limits.maxFrameBytes);
  context_.stats.deltaMerges += static_cast<int64_t>(outbox_.merges() - merges);
  queueBytes_ = outbox_.bytes();
  queueMessages_ = outbox_.size();
  int64_t biggest = context_.stats.queueBytesMax.load();
  while (
      static_cast<int64_t>(outbox_.bytes()) > biggest &&
      !context_.stats.queueBytesMax.compare_exchange_weak(biggest, static_cast<int64_t>(outbox_.bytes()))) {
  }
  writeNext();
}

void Connection::reply(const wire::ServerMessage& message) {
  queue({frameOf(message, context_.config.limits.maxFrameBytes), nullptr});
}

void Connection::reject(uint64_t clientSeq, wire::RejectReason reason, const std::string& text) {
  answer(rejectWith(clientSeq, reason, text));
}

void Connection::answer(const wire::ServerMessage& message) {
  if (message.has_reject()) ++context_.stats.rejects;
  reply(message);
}

CatalogueCaller Connection::caller() {
  return {sessionId_, globalRole_, [this](store::DocumentId id) { return roleFor(id); }};
}

void Connection::fatal(wire::ErrorCode code, const std::string& message) {
  if (closing_ || closed_) return;
  logEvent(LogLevel::kInfo, "connection_error",
           {{"session", sessionId_}, {"code", wire::ErrorCode_Name(code)}, {"message", message}});
  wire::ServerMessage m;
  m.mutable_error()->set_code(code);
  m.mutable_error()->set_message(message);
  m.mutable_error()->set_fatal(true);
  reply(m);
  closing_ = true;
  if (!outbox_.writing() && outbox_.empty()) closeNow();
  if (!transportReady_) closeNow();
}

void Connection::refuse(wire::ErrorCode code, const std::string& message) {
  asio::post(strand_, [self = shared_from_this(), code, message] { self->fatal(code, message); });
}

void Connection::shutdown() {
  asio::post(strand_, [self = shared_from_this()] {
    self->fatal(wire::ERROR_CODE_SHUTTING_DOWN, "the server is stopping");
  });
}

void Connection::writeNext() {
  if (closed_ || outbox_.writing()) return;
  if (!transportReady_) {
    if (closing_) closeNow();  // refused before the transport's handshake: nothing can be said yet
    return;
  }
  if (outbox_.empty()) {
    if (closing_) return closeNow();
    // Documents whose deltas were dropped get a fresh snapshot.
    for (uint64_t doc : outbox_.takeResyncs()) {
      auto host = open_.find(doc);
      auto profile = subscriptions_.find(doc);
      if (host != open_.end() && profile != subscriptions_.end()) {
        host->second->subscribe(shared_from_this(), profile->second, 0, true);  // with its latest view
      }
    }
    for (uint64_t doc : outbox_.takePresenceResyncs()) {
      if (auto host = open_.find(doc); host != open_.end()) host->second->resendPresence(sessionId_);
    }
    return;
  }
  auto frames = outbox_.startWrite(64, 1u << 20);
  const size_t count = frames.size();
  writeStarted_ = std::chrono::steady_clock::now();
  armWriteWatchdog();
  transport_->write(std::move(frames),
                    [self = shared_from_this(), count](const boost::system::error_code& ec, size_t n) {
                      if (self->closed_) return;
                      if (ec) return self->closeNow();
                      self->context_.stats.bytesSent += static_cast<int64_t>(n);
                      self->context_.stats.framesSent += static_cast<int64_t>(count);
                      self->outbox_.finishWrite();
                      self->queueBytes_ = self->outbox_.bytes();
                      self->queueMessages_ = self->outbox_.size();
                      self->writeNext();
                    });
}

// One timer per connection, not one per write: with a thousand subscribers
// and a delta every few milliseconds, arming and cancelling a timer around
// every write costs more than the write. The watchdog wakes when the oldest
// possible deadline passes and re-arms for the write in flight, if any.
void Connection::armWriteWatchdog() {
  if (watchdogArmed_) return;
  watchdogArmed_ = true;
  const auto limit = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(context_.config.timeouts.writeSeconds));
  writeTimer_.expires_at(writeStarted_ + limit);
  writeTimer_.async_wait([self = shared_from_this(), limit](const boost::system::error_code& ec) {
    self->watchdogArmed_ = false;
    if (ec || self->closed_ || !self->outbox_.writing()) return;
    if (std::chrono::steady_clock::now() - self->writeStarted_ >= limit) {
      logEvent(LogLevel::kInfo, "write_timeout", {{"session", self->sessionId_}});
      return self->closeNow();  // the peer stopped reading: nothing more can reach it
    }
    self->armWriteWatchdog();
  });
}

void Connection::closeNow() {
  if (closed_) return;
  closed_ = true;
  live_ = false;
  idleTimer_.cancel();
  writeTimer_.cancel();
  helloTimer_.cancel();
  transport_->close();
  for (auto& [id, host] : open_) host->leave(sessionId_);
  open_.clear();
  logEvent(LogLevel::kInfo, "disconnected", {{"session", sessionId_}});
}

bool Connection::allowedByRate(uint64_t clientSeq, double cost) {
  const double rate = context_.config.limits.commandsPerSecond;
  const auto now = std::chrono::steady_clock::now();
  bucket_ = std::min(rate, bucket_ + rate * std::chrono::duration<double>(now - refilled_).count());
  refilled_ = now;
  // A batch may take the bucket below zero (at most a second's worth): the
  // commands after it wait for the refill, and a batch is never refused
  // only for being larger than what is left.
  cost = std::max(1.0, std::min(cost, rate));
  if (bucket_ >= 1.0) {
    bucket_ -= cost;
    return true;
  }
  reject(clientSeq, wire::REJECT_REASON_RATE_LIMITED,
         "more than " + std::to_string(static_cast<int>(rate)) + " commands per second");
  return false;
}

std::optional<store::Role> Connection::roleFor(store::DocumentId id) {
  if (token_.empty()) return std::nullopt;
  if (auto it = roles_.find(id.value); it != roles_.end()) return it->second;
  auto role = context_.store.roleFor(token_, store::TokenScope::document(id));
  if (!role.isOk()) return std::nullopt;
  roles_[id.value] = *role;
  return *role;
}

void Connection::handle(wire::ClientMessage message) {
  const uint64_t seq = message.client_seq();
  if (!helloDone_) return handleHello(message);
  using C = wire::ClientMessage;
  switch (message.command_case()) {
    case C::kHello:
      return reject(seq, wire::REJECT_REASON_INVALID_STATE, "already said hello");
    case C::kPing: {
      wire::ServerMessage m;
      m.mutable_pong()->set_client_seq(seq);
      m.mutable_pong()->set_server_time_unix_ms(
          static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                    std::chrono::system_clock::now().time_since_epoch())
                                    .count()));
      return reply(m);
    }
    case C::COMMAND_NOT_SET:
      return reject(seq, wire::REJECT_REASON_UNKNOWN_COMMAND, "no command in the message");
    default:
      break;
  }
  if (token_.empty()) {
    return reject(seq, wire::REJECT_REASON_NOT_AUTHENTICATED, "authenticate with a token in Hello first");
  }
  if (message.has_edit_batch() && message.edit_batch().commands_size() > kMaxEditBatchCommands) {
    return reject(seq, wire::REJECT_REASON_LIMIT_EXCEEDED,
                  "edit batch: " + std::to_string(message.edit_batch().commands_size()) +
                      " commands, above the limit of " + std::to_string(kMaxEditBatchCommands) +
                      " per batch (nothing was applied)");
  }
  const double cost = message.has_edit_batch() ? message.edit_batch().commands_size() : 1.0;
  if (!allowedByRate(seq, cost)) return;
  switch (message.command_case()) {
    case C::kListDocuments:
      return answer(listDocuments(context_.store, caller(), seq));
    case C::kStats:
      return answer(serverStats(context_.stats, context_.store, context_.config, seq, outbox_.bytes()));
    case C::kCreateDocument:
      return createDocument(seq, message.create_document());
    case C::kOpenDocument:
      return openDocument(seq, message.open_document().document_id());
    case C::kCloseDocument:
      return closeDocument(seq, message.close_document().document_id());
    case C::kDeleteDocument: {
      const store::DocumentId id{message.delete_document().document_id()};
      wire::ServerMessage answered = deleteDocument(context_.store, context_.opener, caller(), seq, id);
      if (answered.has_ack()) {
        open_.erase(id.value);
        roles_.erase(id.value);
      }
      return answer(answered);
    }
    case C::kGrantToken:
      return answer(grantToken(context_.store, caller(), seq, message.grant_token()));
    default:
      break;
  }
  const uint64_t doc = documentOf(message);
  auto host = openHost(doc, seq);
  if (!host) return;
  switch (message.command_case()) {
    case C::kSubscribe:
      if (!subscriptions_.count(doc) &&
          subscriptions_.size() >= static_cast<size_t>(context_.config.limits.subscriptionsPerSession)) {
        return reject(seq, wire::REJECT_REASON_LIMIT_EXCEEDED,
                      "this session already subscribes " + std::to_string(subscriptions_.size()) +
                          " documents, the limit (--subscriptions-per-session)");
      }
      // A codec the server does not serve is refused before it replaces the
      // subscription a resync would repeat (profile_request.h).
      if (auto codec = codecFromWire(message.subscribe()); !codec.isOk()) {
        return reject(seq, wire::REJECT_REASON_INVALID_ARGUMENT, codec.status().message());
      }
      subscriptions_[doc] = message.subscribe();
      break;
    case C::kSetView:
      // A resync after dropped tiles resubscribes with the latest view.
      if (auto s = subscriptions_.find(doc); s != subscriptions_.end() && s->second.has_view())
        *s->second.mutable_view() = message.set_view().view();
      break;
    case C::kUnsubscribe:
      subscriptions_.erase(doc);
      break;
    default:
      break;
  }
  if (isEditCommand(message)) {
    const auto role = roleFor(store::DocumentId{doc});
    if (!role || *role < store::Role::kEditor) {
      return reject(seq, wire::REJECT_REASON_PERMISSION_DENIED,
                    "editing document " + std::to_string(doc) + " needs the editor role");
    }
    // A second key's mesh is a base mesh: the same limit as CreateDocument's.
    if (message.has_add_morph_key() &&
        message.add_morph_key().mesh().size() > context_.config.limits.maxBaseMeshBytes) {
      return reject(seq, wire::REJECT_REASON_LIMIT_EXCEEDED,
                    "add morph key: the mesh has " + std::to_string(message.add_morph_key().mesh().size()) +
                        " bytes, above the limit of " +
                        std::to_string(context_.config.limits.maxBaseMeshBytes));
    }
  }
  const bool unsubscribe = message.has_unsubscribe();
  if (!dispatchToDocument(*host, shared_from_this(), name_, std::move(message)))
    return reject(seq, wire::REJECT_REASON_UNKNOWN_COMMAND, "unknown command");
  if (unsubscribe) reply(ackFor(seq, doc));
}

void Connection::handleHello(const wire::ClientMessage& message) {
  Status ok = checkHandshake(message);
  if (!ok.isOk()) {
    reply(makeHandshakeError(ok));
    closing_ = true;
    return;
  }
  if (message.hello().token().empty()) return authenticate(message);  // anonymous: nothing to guess
  // A token is judged in its address's turn: after failures from that
  // address, its attempts are spaced (auth_throttle.h). The wait is the
  // server's, so the handshake deadline stops; reading stops too, so
  // nothing after the Hello is handled before it.
  const auto now = std::chrono::steady_clock::now();
  const auto turn = context_.authThrottle.admit(address_, now);
  if (turn <= now) return authenticate(message);
  helloHeld_ = true;
  idleTimer_.cancel();
  helloTimer_.expires_at(turn);
  helloTimer_.async_wait(boost::asio::bind_executor(
      strand_, [self = shared_from_this(), message](const boost::system::error_code& ec) {
        if (ec || self->closed_) return;
        self->helloHeld_ = false;
        self->authenticate(message);
        self->drainFrames();
      }));
}

void Connection::authenticate(const wire::ClientMessage& message) {
  token_ = message.hello().token();
  name_ = message.hello().client_name().empty() ? "session " + std::to_string(sessionId_)
                                                : message.hello().client_name();
  if (!token_.empty()) {
    auto known = context_.store.knowsToken(token_);
    if (!known.isOk()) {
      // The store could not answer (a cluster without quorum, a damaged
      // file): not the client's fault, so no throttling, and it is told why.
      logEvent(LogLevel::kError, "auth_unavailable",
               {{"session", sessionId_}, {"address", address_}, {"error", known.status().message()}});
      token_.clear();
      return fatal(wire::ERROR_CODE_INTERNAL,
                   "cannot check the access token now: " + known.status().message());
    }
    if (!*known) {
      // Never the token itself in a log.
      const int failures = context_.authThrottle.failed(address_, std::chrono::steady_clock::now());
      ++context_.stats.authFailures;
      logEvent(LogLevel::kWarn, "auth_failed",
               {{"session", sessionId_},
                {"address", address_},
                {"name", name_},
                {"recent_failures", static_cast<int64_t>(failures)},
                {"error", "unknown token"}});
      token_.clear();
      return fatal(wire::ERROR_CODE_AUTH_FAILED, "the access token is not known to this server");
    }
    authenticated_ = true;
    auto role = context_.store.roleFor(token_, store::TokenScope::allDocuments());
    if (role.isOk()) globalRole_ = *role;
  }
  helloDone_ = true;
  armIdleTimer(context_.config.timeouts.idleSeconds);
  logEvent(LogLevel::kInfo, "hello",
           {{"session", sessionId_},
            {"name", name_},
            {"token", !token_.empty()},
            {"role", globalRole_ ? store::roleName(*globalRole_) : "per-document"}});
  HelloAckOptions ack;
  ack.clientSeq = message.client_seq();
  ack.serverVersion = kServerVersion;
  ack.sessionId = sessionId_;
  ack.role = globalRole_ ? wireRole(*globalRole_) : wire::ROLE_UNSPECIFIED;
  ack.maxFrameBytes = context_.config.limits.maxFrameBytes;
  reply(makeHelloAck(ack));
}

std::shared_ptr<DocumentEndpoint> Connection::openHost(uint64_t documentId, uint64_t clientSeq) {
  auto it = open_.find(documentId);
  if (it == open_.end()) {
    reject(clientSeq, wire::REJECT_REASON_NOT_OPEN,
           "document " + std::to_string(documentId) + " is not open here");
    return nullptr;
  }
  return it->second;
}

void Connection::createDocument(uint64_t seq, const wire::CreateDocument& request) {
  if (!globalRole_ || *globalRole_ < store::Role::kAdmin) {
    return reject(seq, wire::REJECT_REASON_PERMISSION_DENIED, "creating documents needs an admin token");
  }
  if (request.mesh().size() > context_.config.limits.maxBaseMeshBytes) {
    return reject(seq, wire::REJECT_REASON_LIMIT_EXCEEDED,
                  "create: the mesh has " + std::to_string(request.mesh().size()) +
                      " bytes, above the limit of " +
                      std::to_string(context_.config.limits.maxBaseMeshBytes));
  }
  // Importing is bulk work: off the network threads and off the workers
  // that run documents' edits (docs/ARCHITECTURE.md, "Bulk work").
  asio::post(context_.bulk, [self = shared_from_this(), seq, request] {
    ImportReport report;
    auto doc = importDocument(request, self->context_.config.limits.maxLevel, report);
    Expected<store::DocumentId> id =
        doc.isOk() ? self->context_.store.createDocument(request.name(), serializeDocument(*doc))
                   : Expected<store::DocumentId>(doc.status());
    const wire::SubdivisionScheme scheme = !doc.isOk() ? wire::SUBDIVISION_SCHEME_UNSPECIFIED
                                           : doc->scheme() == DocumentScheme::kCatmullClark
                                               ? wire::SUBDIVISION_SCHEME_CATMULL_CLARK
                                               : wire::SUBDIVISION_SCHEME_LOOP;
    doc = invalidArgument("released");
    ::malloc_trim(0);  // an import of millions of triangles leaves its memory in the heap otherwise
    const uint32_t dropped = static_cast<uint32_t>(report.renumbering.dropped);
    const uint32_t creased = static_cast<uint32_t>(report.edgesCreasedByAngle);
    asio::post(self->strand_, [self, seq, id, dropped, creased, scheme] {
      if (!id.isOk()) return self->answer(rejectFor(seq, id.status()));
      logEvent(LogLevel::kInfo, "document_created", {{"doc", id->value}, {"session", self->sessionId_}});
      wire::ServerMessage ack = ackFor(seq, id->value);
      ack.mutable_ack()->set_version(1);
      ack.mutable_ack()->set_dropped_vertices(dropped);
      ack.mutable_ack()->set_creased_edges(creased);
      ack.mutable_ack()->set_scheme(scheme);
      self->reply(ack);
    });
  });
}

void Connection::openDocument(uint64_t seq, uint64_t documentId) {
  const auto role = roleFor(store::DocumentId{documentId});
  if (!role) {
    return reject(seq, wire::REJECT_REASON_PERMISSION_DENIED,
                  "no access to document " + std::to_string(documentId));
  }
  // Loading replays a journal and may be large: bulk work.
  asio::post(context_.bulk, [self = shared_from_this(), seq, documentId, role = *role] {
    auto host = self->context_.opener.openEndpoint(store::DocumentId{documentId});
    asio::post(self->strand_, [self, seq, documentId, role, host] {
      if (!host.isOk()) return self->answer(rejectFor(seq, host.status()));
      if (self->closed_) return;
      self->open_[documentId] = *host;
      (*host)->join(self, self->name_, wireRole(role));
      wire::ServerMessage ack = ackFor(seq, documentId);
      self->reply(ack);
    });
  });
}

void Connection::closeDocument(uint64_t seq, uint64_t documentId) {
  auto host = openHost(documentId, seq);
  if (!host) return;
  host->leave(sessionId_);
  open_.erase(documentId);
  subscriptions_.erase(documentId);
  wire::ServerMessage ack = ackFor(seq, documentId);
  reply(ack);
}

}  // namespace tessera::server
