#include "client/replay/viewer_pool.h"

#include <array>
#include <boost/asio/bind_executor.hpp>
#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>
#include <boost/asio/write.hpp>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "client/lib/session.h"
#include "protocol/framing.h"
#include "protocol/handshake.h"

namespace tessera::replay {

namespace {

namespace asio = boost::asio;
using tcp = asio::ip::tcp;

class Pool;

// One viewer: connect -> Hello -> OpenDocument -> Subscribe -> count. All of
// its handlers run on its own strand.
class PoolViewer : public std::enable_shared_from_this<PoolViewer> {
 public:
  PoolViewer(Pool& pool, asio::io_context& io, int index, ViewerResult& out)
      : pool_(pool), strand_(asio::make_strand(io)), socket_(strand_), index_(index), out_(out) {}

  // Takes one of the pool's joining places (given back by joined()).
  void start(const tcp::resolver::results_type& endpoints);
  // From the pool's clock, on any thread: ping, move the camera, or close
  // when the run is over.
  void tick(bool pingDue);
  void close();

 private:
  enum class Stage { kHello, kOpen, kSubscribe, kStreaming, kClosed };

  void connect(const tcp::resolver::results_type& endpoints);
  std::string name() const { return "viewer-" + std::to_string(index_ + 1); }
  void send(wire::ClientMessage message);
  void writeNext();
  void read();
  // Deltas are counted from their header alone; anything else is parsed.
  void handle(const std::string& payload, Clock::time_point arrival);
  void handle(const wire::ServerMessage& m, Clock::time_point arrival);
  void fail(const std::string& message);
  void joined();

  Pool& pool_;
  asio::strand<asio::io_context::executor_type> strand_;
  tcp::socket socket_;
  const int index_;
  ViewerResult& out_;
  Stage stage_ = Stage::kHello;
  bool joining_ = false;  // holds one of the pool's joining places
  uint64_t nextSeq_ = 1, openSeq_ = 0, subscribeSeq_ = 0;
  Clock::time_point lastView_ = Clock::now();  // the last SetView sent (camera paths)
  FrameDecoder decoder_;
  std::array<char, 16 * 1024> buffer_{};
  std::deque<std::string> outbox_;
};

class Pool {
 public:
  Pool(const LoadOptions& o, const ViewerPoolOptions& p, Clock::time_point hardDeadline, Shared& shared)
      : o_(o), p_(p), hardDeadline_(hardDeadline), shared_(shared), timer_(io_) {}

  void run(std::span<ViewerResult> results) {
    tcp::resolver resolver(io_);
    boost::system::error_code ec;
    endpoints_ = resolver.resolve(o_.session.host, std::to_string(o_.session.port), ec);
    if (ec) {
      shared_.error("viewer pool: cannot resolve " + o_.session.host + ": " + ec.message());
      shared_.viewersDone += static_cast<int64_t>(results.size());
      return;
    }
    for (size_t i = 0; i < results.size(); ++i) {
      viewers_.push_back(
          std::make_shared<PoolViewer>(*this, io_, p_.firstIndex + static_cast<int>(i), results[i]));
    }
    startMore();
    tick();
    std::vector<std::thread> threads;
    for (int t = 1; t < p_.threads; ++t) threads.emplace_back([this] { io_.run(); });
    io_.run();
    for (auto& t : threads) t.join();
  }

  const LoadOptions& options() const { return o_; }
  Shared& shared() { return shared_; }

  // A viewer finished joining (ready or failed): let the next one start.
  void joinDone() {
    std::lock_guard lock(mu_);
    --joining_;
    asio::post(io_, [this] { startMore(); });
  }
  void viewerDone() {
    ++shared_.viewersDone;
    std::lock_guard lock(mu_);
    ++done_;
  }

 private:
  void startMore() {
    std::lock_guard lock(mu_);
    while (joining_ < p_.maxJoining && next_ < viewers_.size()) {
      ++joining_;
      viewers_[next_++]->start(endpoints_);
    }
  }

  // Every 50 ms: pings every 30 s, and the end of the run.
  void tick() {
    const auto now = Clock::now();
    if (shared_.stopViewing && !stopSeen_) stopSeen_ = now;
    const bool over = now > hardDeadline_ || shared_.stopped ||
                      (stopSeen_ && now - *stopSeen_ > std::chrono::duration<double>(o_.drainSeconds));
    const bool pingDue = now - lastPing_ > std::chrono::seconds(30);
    if (pingDue) lastPing_ = now;
    if (over || pingDue || shared_.stopViewing || o_.cameras) {
      for (auto& v : viewers_) over ? v->close() : v->tick(pingDue);
    }
    {
      std::lock_guard lock(mu_);
      if (over || done_ == viewers_.size()) return;  // nothing more to wait for: io_.run() returns
    }
    timer_.expires_after(std::chrono::milliseconds(50));
    timer_.async_wait([this](const boost::system::error_code&) { tick(); });
  }

  const LoadOptions& o_;
  const ViewerPoolOptions& p_;
  const Clock::time_point hardDeadline_;
  Shared& shared_;
  asio::io_context io_;
  asio::steady_timer timer_;
  tcp::resolver::results_type endpoints_;
  std::vector<std::shared_ptr<PoolViewer>> viewers_;
  std::mutex mu_;  // guards what follows
  size_t next_ = 0, done_ = 0;
  int joining_ = 0;
  std::optional<Clock::time_point> stopSeen_;
  Clock::time_point lastPing_ = Clock::now();
};

void PoolViewer::start(const tcp::resolver::results_type& endpoints) {
  asio::post(strand_, [self = shared_from_this(), endpoints] {
    if (self->stage_ == Stage::kClosed) return self->pool_.joinDone();
    self->joining_ = true;
    self->decoder_ = FrameDecoder({self->pool_.options().session.maxFrameBytes});
    self->connect(endpoints);
  });
}

void PoolViewer::connect(const tcp::resolver::results_type& endpoints) {
  asio::async_connect(
      socket_, endpoints,
      asio::bind_executor(
          strand_, [self = shared_from_this()](const boost::system::error_code& ec, const tcp::endpoint&) {
            if (ec) return self->fail("connect: " + ec.message());
            HelloOptions hello;
            hello.clientSeq = self->nextSeq_++;
            hello.clientName = self->name();
            const LoadOptions& o = self->pool_.options();
            hello.token = o.viewerToken.empty() ? o.session.token : o.viewerToken;
            self->send(makeHello(hello));
            self->read();
          }));
}

void PoolViewer::tick(bool pingDue) {
  asio::post(strand_, [self = shared_from_this(), pingDue] {
    if (self->stage_ != Stage::kStreaming) return;
    Shared& shared = self->pool_.shared();
    if (shared.stopViewing && self->out_.ready && self->out_.version >= shared.maxAckedVersion.load())
      return self->close();
    if (pingDue) {
      wire::ClientMessage ping;
      ping.mutable_ping();
      self->send(std::move(ping));
    }
    // A camera path: the view now, at the path's rate, while the run lasts.
    if (!shared.stopViewing && self->out_.ready) {
      if (auto view = viewIfDue(self->pool_.options(), self->index_, shared, self->lastView_))
        self->send(std::move(*view));
    }
  });
}

void PoolViewer::close() {
  asio::post(strand_, [self = shared_from_this()] {
    if (self->stage_ == Stage::kClosed) return;
    self->stage_ = Stage::kClosed;
    self->joined();
    boost::system::error_code ignored;
    self->socket_.shutdown(tcp::socket::shutdown_both, ignored);
    self->socket_.close(ignored);
    self->pool_.viewerDone();
  });
}

void PoolViewer::joined() {
  if (!joining_) return;
  joining_ = false;
  pool_.joinDone();
}

void PoolViewer::fail(const std::string& message) {
  if (stage_ == Stage::kClosed) return;
  pool_.shared().error(name() + ": " + message);
  close();
}

void PoolViewer::send(wire::ClientMessage message) {
  if (message.client_seq() == 0) message.set_client_seq(nextSeq_++);
  auto frame = encodeFrame(message, pool_.options().session.maxFrameBytes);
  if (!frame.isOk()) return fail(frame.status().message());
  outbox_.push_back(std::move(*frame));
  if (outbox_.size() == 1) writeNext();
}

void PoolViewer::writeNext() {
  asio::async_write(
      socket_, asio::buffer(outbox_.front()),
      asio::bind_executor(strand_, [self = shared_from_this()](const boost::system::error_code& ec, size_t) {
        if (self->stage_ == Stage::kClosed) return;
        if (ec) return self->fail("send: " + ec.message());
        self->outbox_.pop_front();
        if (!self->outbox_.empty()) self->writeNext();
      }));
}

void PoolViewer::read() {
  socket_.async_read_some(
      asio::buffer(buffer_), asio::bind_executor(strand_, [self = shared_from_this()](
                                                              const boost::system::error_code& ec, size_t n) {
        if (self->stage_ == Stage::kClosed) return;
        if (ec) return self->fail("connection closed: " + ec.message());
        const auto arrival = Clock::now();
        if (Status fed = self->decoder_.feed(std::string_view(self->buffer_.data(), n)); !fed.isOk()) {
          return self->fail(fed.message());
        }
        for (std::string payload;;) {
          auto got = self->decoder_.nextPayload(payload);
          if (!got.isOk()) return self->fail(got.status().message());
          if (!*got) break;
          self->handle(payload, arrival);
          if (self->stage_ == Stage::kClosed) return;
        }
        self->read();
      }));
}

void PoolViewer::handle(const std::string& payload, Clock::time_point arrival) {
  const LoadOptions& o = pool_.options();
  if (stage_ == Stage::kStreaming) {
    if (auto delta = peekDelta(payload)) {
      const int64_t bytes = static_cast<int64_t>(payload.size() + kFrameHeaderBytes);
      if (trackDelta(*delta, bytes, arrival, o.document, out_, pool_.shared()) == ViewerEvent::kGap) {
        subscribeSeq_ = nextSeq_;
        send(subscribeMessage(o, index_, pool_.shared()));
      }
      return;
    }
  }
  wire::ServerMessage m;
  if (!m.ParseFromString(payload))
    return fail("a " + std::to_string(payload.size()) + "-byte frame is not a ServerMessage");
  handle(m, arrival);
}

void PoolViewer::handle(const wire::ServerMessage& m, Clock::time_point arrival) {
  const LoadOptions& o = pool_.options();
  if (stage_ == Stage::kHello) {
    if (Status st = checkHelloAck(m); !st.isOk()) return fail(st.message());
    wire::ClientMessage open;
    open.mutable_open_document()->set_document_id(o.document);
    openSeq_ = nextSeq_;
    send(std::move(open));
    stage_ = Stage::kOpen;
    return;
  }
  const uint64_t reply = client::replyTo(m);
  if (reply != 0 && m.has_reject() && (reply == openSeq_ || reply == subscribeSeq_)) {
    return fail(wire::RejectReason_Name(m.reject().reason()) + ": " + m.reject().message());
  }
  if (stage_ == Stage::kOpen && reply == openSeq_) {
    subscribeSeq_ = nextSeq_;
    send(subscribeMessage(o, index_, pool_.shared()));
    stage_ = Stage::kSubscribe;
    return;
  }
  if (stage_ == Stage::kSubscribe && reply == subscribeSeq_) stage_ = Stage::kStreaming;
  switch (trackViewerMessage(m, arrival, o.document, out_, pool_.shared())) {
    case ViewerEvent::kReady:
      joined();
      break;
    case ViewerEvent::kGap:
      subscribeSeq_ = nextSeq_, send(subscribeMessage(o, index_, pool_.shared()));
      break;
    case ViewerEvent::kFatal:
      fail("server error: " + m.error().message());
      break;
    case ViewerEvent::kNone:
      break;
  }
}

}  // namespace

void runViewerPool(const LoadOptions& options, const ViewerPoolOptions& pool, Clock::time_point hardDeadline,
                   Shared& shared, std::span<ViewerResult> results) {
  if (results.empty()) return;
  Pool p(options, pool, hardDeadline, shared);
  p.run(results);
}

}  // namespace tessera::replay
