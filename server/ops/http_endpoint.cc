#include "server/ops/http_endpoint.h"

#include <atomic>
#include <boost/asio/dispatch.hpp>
#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <exception>
#include <optional>
#include <thread>
#include <vector>

#include "server/base/http_requests.h"
#include "server/base/log.h"

namespace tessera::server {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;

namespace {

constexpr int kThreads = 2;
constexpr int kMaxConnections = 32;  // a scraper and a few probes need one each
// To send a request (or the next one on a kept-alive connection), and to
// take an answer: then the connection is closed.
constexpr auto kRequestTimeout = std::chrono::seconds(5);
constexpr auto kWriteTimeout = std::chrono::seconds(5);

// One connection to the endpoint: requests read and answered in turn, on
// the connection's strand.
class EndpointSession : public std::enable_shared_from_this<EndpointSession> {
 public:
  EndpointSession(EndpointPages& pages, std::atomic<int>& connections, tcp::socket socket)
      : pages_(pages), connections_(connections), stream_(std::move(socket)) {}
  ~EndpointSession() { --connections_; }

  void start() {
    asio::dispatch(stream_.get_executor(), [self = shared_from_this()] { self->readRequest(); });
  }

 private:
  void readRequest() {
    parser_.emplace();
    limitToHeaders(*parser_);
    stream_.expires_after(kRequestTimeout);
    http::async_read(
        stream_, buffer_, *parser_,
        [self = shared_from_this()](const beast::error_code& ec, size_t) { self->onRequest(ec); });
  }

  void onRequest(const beast::error_code& ec) {
    if (ec) {
      const auto unreadable = unreadableRequest(ec);
      if (!unreadable) return closeSocket(stream_.socket());
      return send(textResponse(unreadable->status, unreadable->reason, false));
    }
    const auto& request = parser_->get();
    ++requests_;
    if (request.method() != http::verb::get && request.method() != http::verb::head) {
      return send(textResponse(http::status::method_not_allowed, "only GET and HEAD are served here", false));
    }
    const std::string_view target(request.target().data(), request.target().size());
    EndpointPage page;
    try {
      page = pages_.get(target.substr(0, target.find('?')));
    } catch (const std::exception& e) {
      // A source that throws fails this answer, not the endpoint's thread.
      logEvent(LogLevel::kError, "http_failed", {{"target", std::string(target)}, {"error", e.what()}});
      return send(textResponse(http::status::internal_server_error, "internal error", false));
    }
    TextResponse response(static_cast<http::status>(page.status), request.version());
    serverHeaders(response);
    response.set(http::field::content_type, page.contentType);
    if (request.method() == http::verb::head) {
      response.content_length(page.body.size());
    } else {
      response.body() = std::move(page.body);
      response.prepare_payload();
    }
    response.keep_alive(request.keep_alive() && requests_ < kRequestsPerConnection);
    send(std::move(response));
  }

  void send(TextResponse response) {
    auto held = std::make_shared<TextResponse>(std::move(response));
    stream_.expires_after(kWriteTimeout);
    http::async_write(stream_, *held, [self = shared_from_this(), held](const beast::error_code& ec, size_t) {
      if (ec || !held->keep_alive()) return closeSocket(self->stream_.socket());
      self->readRequest();
    });
  }

  EndpointPages& pages_;
  std::atomic<int>& connections_;
  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::optional<RequestParser> parser_;
  int requests_ = 0;
};

}  // namespace

struct HttpEndpoint::Impl {
  explicit Impl(HttpSources sources) : pages(std::move(sources)) {}

  // Declared before the io_context: the sessions its unfinished handlers
  // hold, destroyed with it, still count themselves out.
  EndpointPages pages;
  std::atomic<int> connections{0};
  asio::io_context io;
  tcp::acceptor acceptor{asio::make_strand(io)};
  asio::steady_timer sampler{io};
  asio::executor_work_guard<asio::io_context::executor_type> work = asio::make_work_guard(io);
  std::vector<std::thread> threads;

  Status bind(const std::string& address, int port);

  void accept() {
    acceptor.async_accept(asio::make_strand(io),
                          [this](const boost::system::error_code& ec, tcp::socket socket) {
                            if (ec == asio::error::operation_aborted) return;
                            if (!ec) admit(std::move(socket));
                            accept();
                          });
  }

  void admit(tcp::socket socket) {
    if (connections.load() >= kMaxConnections) {
      boost::system::error_code ignored;
      const std::string address = socket.remote_endpoint(ignored).address().to_string();
      const std::string reason =
          "more than " + std::to_string(kMaxConnections) + " connections to the HTTP endpoint";
      logEvent(LogLevel::kWarn, "connection_refused",
               {{"address", address}, {"reason", reason}, {"port", "http"}});
      return turnAway(std::move(socket), reason);
    }
    ++connections;
    std::make_shared<EndpointSession>(pages, connections, std::move(socket))->start();
  }

  void sample() {
    pages.sampleEdits();
    sampler.expires_after(std::chrono::seconds(1));
    sampler.async_wait([this](const boost::system::error_code& ec) {
      if (!ec) sample();
    });
  }
};

// The address may be a name (--http-listen localhost): the first of its
// addresses that binds is the endpoint's.
Status HttpEndpoint::Impl::bind(const std::string& address, int port) {
  boost::system::error_code ec;
  const auto endpoints = tcp::resolver(io).resolve(
      address, std::to_string(port), tcp::resolver::passive | tcp::resolver::numeric_service, ec);
  if (ec || endpoints.empty()) {
    return invalidArgument("--http-listen: bad address '" + address + "'" + (ec ? ": " + ec.message() : ""));
  }
  for (const auto& entry : endpoints) {
    acceptor.open(entry.endpoint().protocol(), ec);
    if (!ec) acceptor.set_option(tcp::acceptor::reuse_address(true), ec);
    if (!ec) acceptor.bind(entry.endpoint(), ec);
    if (!ec) acceptor.listen(asio::socket_base::max_listen_connections, ec);
    if (!ec) return Status::ok();
    boost::system::error_code ignored;
    acceptor.close(ignored);
  }
  return ioError("--http-port: cannot listen on " + address + ":" + std::to_string(port) + ": " +
                 ec.message());
}

HttpEndpoint::HttpEndpoint(std::unique_ptr<Impl> impl, uint16_t port) : impl_(std::move(impl)), port_(port) {}

Expected<std::unique_ptr<HttpEndpoint>> HttpEndpoint::start(const std::string& address, int port,
                                                            HttpSources sources) {
  auto impl = std::make_unique<Impl>(std::move(sources));
  TESSERA_RETURN_IF_ERROR(impl->bind(address, port));
  const uint16_t bound = impl->acceptor.local_endpoint().port();
  impl->sample();
  impl->accept();
  Impl* raw = impl.get();
  for (int i = 0; i < kThreads; ++i) impl->threads.emplace_back([raw] { raw->io.run(); });
  logEvent(LogLevel::kInfo, "http_listening", {{"address", address}, {"port", static_cast<int64_t>(bound)}});
  return std::unique_ptr<HttpEndpoint>(new HttpEndpoint(std::move(impl), bound));
}

HttpEndpoint::~HttpEndpoint() {
  // Stops at once: answers under way are dropped, their connections closed
  // when the io_context goes.
  impl_->io.stop();
  for (auto& thread : impl_->threads) thread.join();
}

}  // namespace tessera::server
