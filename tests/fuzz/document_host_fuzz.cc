// The whole command path of a server document host (server/document/document_host.h)
// in-process: a sequence of client messages, decoded from the input as the
// server decodes a connection's stream, against a creased-cube document of
// max level kFuzzDocumentLevel (fuzz_support.h says why it is 2).
//
// Input: byte 0 sets the run up (bit 0: the store refuses the third append,
// so the journal-failure path runs; bit 1: --deltas-after-durable); the rest
// is a stream of frames (protocol/framing.h), at most 24 ClientMessages.
// Each message is routed by dispatchToDocument
// (server/document/document_dispatch.h), the routing the connection uses
// after its session checks (subscribe, unsubscribe, select, export, the
// edits and edit batches, a second morph key and the morph's control
// points), from one of two
// sessions (the low bit of client_seq picks which), both joined, one as an
// editor and one as a viewer, and the host's strand runs between messages
// as a server's workers would (one io_context serves as both the worker
// pool and the bulk lane, so bulk work runs in order with the rest). Asio's io_context is polled, never run,
// so timers that are not due yet (the 100 ms presence broadcast) do not make an input wait; their handlers
// are dropped with the io_context.
//
// Oracles besides the sanitizers: every frame the host queues decodes as a
// ServerMessage, and no Reject carries an internal error unless the store
// was told to fail.
#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <memory>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "protocol/framing.h"
#include "protocol/tessera.pb.h"
#include "server/base/log.h"
#include "server/document/document_dispatch.h"
#include "server/document/document_host.h"
#include "tests/support/host_only_store.h"

namespace tessera::fuzz {
namespace {

using server::Outgoing;

// A store for one document host: appends complete on the io_context, as a
// real store's callbacks arrive from its writer thread; the rest is unused.
class PostingStore final : public testing::HostOnlyStore {
 public:
  explicit PostingStore(int failAppend) : failAppend_(failAppend) {}
  void attach(boost::asio::io_context& io) { io_ = &io; }
  void append(store::DocumentId, uint64_t, std::string, std::string bytes,
              store::AppendCallback done) override {
    require(!bytes.empty(), "the host journaled an empty entry");
    const bool refuse = ++appends_ == failAppend_;
    boost::asio::post(*io_, [done = std::move(done), refuse] {
      done(refuse ? ioError("fuzz store: append refused") : Status::ok());
    });
  }

 private:
  boost::asio::io_context* io_ = nullptr;
  const int failAppend_;
  int appends_ = 0;
};

// Checks every frame the host queues for a session.
class Inbox final : public server::Subscriber {
 public:
  Inbox(uint64_t session, bool internalAllowed) : session_(session), internalAllowed_(internalAllowed) {}
  uint64_t sessionId() const override { return session_; }
  void send(Outgoing message) override {
    require(message.frame != nullptr, "the host queued a null frame");
    FrameDecoder decoder({.maxFrameBytes = 1u << 30});
    wire::ServerMessage m;
    checkError(decoder.feed(*message.frame), "a frame the host queued");
    auto got = decoder.next(m);
    require(got.isOk() && *got, "a frame the host queued does not decode");
    require(!decoder.next(m).isOk() || decoder.bufferedBytes() == 0,
            "a queued frame holds more than one message");
    if (m.has_reject() && !internalAllowed_) {
      require(m.reject().reason() != wire::REJECT_REASON_INTERNAL,
              "an internal error: " + m.reject().message());
    }
  }

 private:
  const uint64_t session_;
  const bool internalAllowed_;
};

server::ServerConfig makeConfig(bool deltasAfterDurable) {
  server::ServerConfig config;
  config.deltaFramesPerSecond = 0;  // no pacing: a flush follows each edit, so no timer holds it
  config.deltaIntervalMs = 0;
  config.deltasAfterDurable = deltasAfterDurable;
  config.limits.maxTrianglesPerSubscriber = 20000;  // a level-3 cube has 768 triangles
  config.limits.maxFrameBytes = 1u << 20;
  return config;
}

// As the connection routes them (its session checks aside): the one routing.
void route(server::DocumentHost& host, const std::shared_ptr<Inbox>& who, wire::ClientMessage message) {
  const std::string author = "session " + std::to_string(who->sessionId());
  server::dispatchToDocument(host, who, author, std::move(message));
}

void pollAll(boost::asio::io_context& io) {
  io.restart();
  while (io.poll() > 0) io.restart();
}

}  // namespace
}  // namespace tessera::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  using namespace tessera::fuzz;
  if (size < 1) return 0;
  // The host's info lines (a document opened and closed per input) would
  // fill a long run's log; warnings and errors stay.
  static const bool quiet = (server::setLogLevel(server::LogLevel::kWarn), true);
  (void)quiet;
  const bool failStore = (data[0] & 1) != 0;
  static const server::ServerConfig configs[2] = {makeConfig(false), makeConfig(true)};
  const server::ServerConfig& config = configs[(data[0] >> 1) & 1];
  server::ServerStats stats;
  PostingStore store(failStore ? 3 : 0);
  // Destroyed before the store and the stats: it destroys the handlers
  // still waiting (timers), and with them the host, which refers to both.
  boost::asio::io_context io;
  store.attach(io);
  {
    auto host = std::make_shared<server::DocumentHost>(
        store::DocumentId{1}, "cube", KeyedDocument(cubeDocument(kFuzzDocumentLevel)), 1, io.get_executor(),
        io.get_executor(), store, config, stats);
    std::shared_ptr<Inbox> sessions[2] = {std::make_shared<Inbox>(1, failStore),
                                          std::make_shared<Inbox>(2, failStore)};
    host->join(sessions[0], "editor", wire::ROLE_EDITOR);
    host->join(sessions[1], "viewer", wire::ROLE_VIEWER);
    pollAll(io);

    FrameDecoder decoder({.maxFrameBytes = 1u << 16});
    (void)decoder.feed(std::string_view(reinterpret_cast<const char*>(data + 1), size - 1));
    wire::ClientMessage message;
    for (int n = 0; n < 24; ++n) {
      auto got = decoder.next(message);
      if (!got.isOk() || !*got) break;
      route(*host, sessions[message.client_seq() & 1], std::move(message));
      pollAll(io);
    }
    for (auto& s : sessions) host->leave(s->sessionId());
    pollAll(io);
  }
  return 0;
}
