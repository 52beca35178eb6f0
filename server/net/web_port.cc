#include "server/net/web_port.h"

#include <algorithm>
#include <boost/asio/bind_executor.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket/rfc6455.hpp>
#include <map>
#include <mutex>
#include <optional>

#include "server/base/http_requests.h"
#include "server/base/log.h"
#include "server/net/websocket_transport.h"

namespace tessera::server {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;

namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::chrono::steady_clock::duration secondsOf(double seconds) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(seconds));
}

// The peers not yet upgraded (or only fetching files): bounded per address
// and in all, like the protocol port's unauthenticated connections.
class PeerCount {
 public:
  explicit PeerCount(const Limits& limits)
      : perAddress_(limits.unauthenticatedPerAddress), total_(limits.unauthenticatedTotal) {}

  // Takes a slot for `address`, or says why not.
  std::optional<std::string> take(const std::string& address) {
    std::lock_guard lock(mutex_);
    int& here = byAddress_[address];
    if (here >= perAddress_) {
      return "more than " + std::to_string(perAddress_) + " unauthenticated connections from " + address +
             " (--unauthenticated-per-address)";
    }
    if (all_ >= total_) {
      return "more than " + std::to_string(total_) +
             " unauthenticated connections in all (--unauthenticated-total)";
    }
    ++here;
    ++all_;
    return std::nullopt;
  }

  void give(const std::string& address) {
    std::lock_guard lock(mutex_);
    auto it = byAddress_.find(address);
    if (it != byAddress_.end() && --it->second == 0) byAddress_.erase(it);
    --all_;
  }

 private:
  std::mutex mutex_;
  const int perAddress_, total_;
  std::map<std::string, int> byAddress_;
  int all_ = 0;
};

}  // namespace

struct WebPort::Impl : std::enable_shared_from_this<WebPort::Impl> {
  Impl(asio::io_context& io, WebPortOptions o, StaticFiles f, OnUpgrade u)
      : io(io),
        acceptor(asio::make_strand(io)),
        options(std::move(o)),
        files(std::move(f)),
        onUpgrade(std::move(u)),
        peers(options.limits) {}

  asio::io_context& io;
  tcp::acceptor acceptor;
  WebPortOptions options;
  StaticFiles files;
  OnUpgrade onUpgrade;
  PeerCount peers;
  uint16_t port = 0;  // bound
  bool stopped = false;

  void accept();
  // Whether a browser on `origin` may open a WebSocket to a page served as
  // `host`: its own page always, others only when --ws-allowed-origin names
  // them. Requests without an Origin are not from a browser page.
  bool originAllowed(std::string_view origin, std::string_view host) const {
    if (origin.empty()) return true;
    const std::string o = lower(origin);
    if (o == lower(std::string(options.tls ? "https://" : "http://") + std::string(host))) return true;
    for (const auto& allowed : options.allowedOrigins) {
      if (allowed == "*" || lower(allowed) == o) return true;
    }
    return false;
  }
};

namespace {

// One HTTP connection of the web port, until it upgrades or closes.
template <typename Stream>
class WebSession : public PendingUpgrade, public std::enable_shared_from_this<WebSession<Stream>> {
 public:
  WebSession(std::shared_ptr<WebPort::Impl> port, Stream stream, std::string address)
      : port_(std::move(port)), stream_(std::move(stream)), address_(std::move(address)) {}
  ~WebSession() override { releaseSlot(); }

  void start() {
    auto self = this->shared_from_this();
    if constexpr (std::is_same_v<Stream, beast::tcp_stream>) {
      asio::dispatch(stream_.get_executor(), [self] { self->readRequest(); });
    } else {
      beast::get_lowest_layer(stream_).expires_after(secondsOf(port_->options.timeouts.handshakeSeconds));
      stream_.async_handshake(asio::ssl::stream_base::server, [self](const beast::error_code& ec) {
        if (ec) return self->closeSocket();
        self->readRequest();
      });
    }
  }

  // PendingUpgrade
  const std::string& address() const override { return address_; }
  asio::any_io_executor executor() override { return beast::get_lowest_layer(stream_).get_executor(); }
  std::unique_ptr<Transport> accept(const ConnectionStrand& strand) override {
    releaseSlot();
    WebSocketLimits limits{uint64_t{port_->options.limits.maxFrameBytes} + 4,
                           port_->options.timeouts.handshakeSeconds};
    return makeWebSocketTransport(std::move(stream_), parser_->release(), strand, limits);
  }
  void refuse(const std::string& reason) override {
    auto self = this->shared_from_this();
    asio::dispatch(beast::get_lowest_layer(stream_).get_executor(),
                   [self, reason] { self->respond(http::status::service_unavailable, reason, false); });
  }

 private:
  void readRequest() {
    parser_.emplace();
    limitToHeaders(*parser_);
    beast::get_lowest_layer(stream_).expires_after(secondsOf(port_->options.timeouts.handshakeSeconds));
    auto self = this->shared_from_this();
    http::async_read(stream_, buffer_, *parser_,
                     [self](const beast::error_code& ec, size_t) { self->onRequest(ec); });
  }

  void onRequest(const beast::error_code& ec) {
    if (ec) {
      const auto unreadable = unreadableRequest(ec);
      return unreadable ? respond(unreadable->status, unreadable->reason, false) : closeSocket();
    }
    const auto& request = parser_->get();
    ++requests_;
    const std::string_view target(request.target().data(), request.target().size());
    const std::string_view path = target.substr(0, target.find('?'));
    if (beast::websocket::is_upgrade(request)) return upgrade(request, path);
    if (request.method() != http::verb::get && request.method() != http::verb::head) {
      return respond(http::status::method_not_allowed, "only GET and HEAD are served here", false);
    }
    const StaticFile* file = port_->files.find(target);
    if (file == nullptr) {
      const bool keep = request.keep_alive();
      return respond(http::status::not_found, "not found (the viewer is at /?doc=ID)", keep);
    }
    serveFile(request, *file);
  }

  void upgrade(const http::request<http::empty_body>& request, std::string_view path) {
    if (path != "/ws") return respond(http::status::not_found, "WebSocket connections go to /ws", false);
    const std::string_view origin(request[http::field::origin].data(), request[http::field::origin].size());
    const std::string_view host(request[http::field::host].data(), request[http::field::host].size());
    if (!port_->originAllowed(origin, host)) {
      logEvent(LogLevel::kWarn, "websocket_origin_refused",
               {{"address", address_}, {"origin", std::string(origin)}});
      return respond(http::status::forbidden,
                     "origin " + std::string(origin) + " may not connect (--ws-allowed-origin)", false);
    }
    beast::get_lowest_layer(stream_).expires_never();
    port_->onUpgrade(this->shared_from_this());
  }

  void serveFile(const http::request<http::empty_body>& request, const StaticFile& file) {
    const auto encodings = request[http::field::accept_encoding];
    const bool gzip =
        !file.gzipped.empty() &&
        lower(std::string_view(encodings.data(), encodings.size())).find("gzip") != std::string::npos;
    // The body points into the port's files, which outlive the response
    // (it holds port_): no copy per request.
    auto response =
        std::make_shared<http::response<http::span_body<const char>>>(http::status::ok, request.version());
    headers(*response);
    response->set(http::field::content_type, file.contentType);
    response->set(http::field::cache_control, "no-cache");
    response->set(http::field::vary, "Accept-Encoding");
    if (gzip) response->set(http::field::content_encoding, "gzip");
    const std::string& body = gzip ? file.gzipped : file.body;
    if (request.method() == http::verb::head) {
      response->content_length(body.size());
    } else {
      response->body() = http::span_body<const char>::value_type(body.data(), body.size());
      response->prepare_payload();
    }
    response->keep_alive(request.keep_alive() && requests_ < kRequestsPerConnection);
    send(response);
  }

  void respond(http::status status, const std::string& text, bool keepAlive) {
    auto response = std::make_shared<TextResponse>(
        textResponse(status, text, keepAlive && requests_ < kRequestsPerConnection));
    headers(*response);
    send(response);
  }

  template <class Body>
  static void headers(http::response<Body>& response) {
    serverHeaders(response);
    response.set("Referrer-Policy", "no-referrer");
    // The page loads only its own files and talks only to its own host;
    // WebAssembly needs 'wasm-unsafe-eval' to compile the Draco decoder.
    response.set("Content-Security-Policy",
                 "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; connect-src 'self' ws: wss:; "
                 "img-src 'self' data:; style-src 'self'; frame-ancestors 'none'");
  }

  template <class Body>
  void send(std::shared_ptr<http::response<Body>> response) {
    beast::get_lowest_layer(stream_).expires_after(secondsOf(port_->options.timeouts.writeSeconds));
    auto self = this->shared_from_this();
    http::async_write(stream_, *response, [self, response](const beast::error_code& ec, size_t) {
      if (ec || !response->keep_alive()) return self->closeSocket();
      self->readRequest();
    });
  }

  void closeSocket() { server::closeSocket(beast::get_lowest_layer(stream_).socket()); }

  void releaseSlot() {
    if (slot_) port_->peers.give(address_);
    slot_ = false;
  }

 public:
  bool slot_ = false;  // holds one of PeerCount's slots

 private:
  std::shared_ptr<WebPort::Impl> port_;
  Stream stream_;
  std::string address_;
  beast::flat_buffer buffer_;
  std::optional<RequestParser> parser_;
  int requests_ = 0;
};

}  // namespace

void WebPort::Impl::accept() {
  acceptor.async_accept(asio::make_strand(io), [self = shared_from_this()](
                                                   const boost::system::error_code& ec, tcp::socket socket) {
    if (ec) {
      if (!self->stopped && ec != asio::error::operation_aborted) self->accept();
      return;
    }
    boost::system::error_code ignored;
    socket.set_option(tcp::no_delay(true), ignored);
    const std::string address = socket.remote_endpoint(ignored).address().to_string();
    if (auto over = self->peers.take(address)) {
      logEvent(LogLevel::kWarn, "connection_refused",
               {{"address", address}, {"reason", *over}, {"port", "web"}});
      turnAway(std::move(socket), *over);
    } else if (self->options.tls != nullptr) {
      auto session = std::make_shared<WebSession<beast::ssl_stream<beast::tcp_stream>>>(
          self,
          beast::ssl_stream<beast::tcp_stream>(beast::tcp_stream(std::move(socket)), *self->options.tls),
          address);
      session->slot_ = true;
      session->start();
    } else {
      auto session = std::make_shared<WebSession<beast::tcp_stream>>(
          self, beast::tcp_stream(std::move(socket)), address);
      session->slot_ = true;
      session->start();
    }
    self->accept();
  });
}

WebPort::WebPort(std::shared_ptr<Impl> impl) : impl_(std::move(impl)) {}

WebPort::~WebPort() {
  stop();
}

Expected<std::unique_ptr<WebPort>> WebPort::start(asio::io_context& io, WebPortOptions options,
                                                  StaticFiles files, OnUpgrade onUpgrade) {
  auto impl = std::make_shared<Impl>(io, std::move(options), std::move(files), std::move(onUpgrade));
  boost::system::error_code ec;
  const auto address = asio::ip::make_address(impl->options.address, ec);
  if (ec) return invalidArgument("--ws-port: bad address '" + impl->options.address + "'");
  const tcp::endpoint endpoint(address, static_cast<uint16_t>(impl->options.port));
  impl->acceptor.open(endpoint.protocol(), ec);
  if (!ec) impl->acceptor.set_option(tcp::acceptor::reuse_address(true), ec);
  if (!ec) impl->acceptor.bind(endpoint, ec);
  if (!ec) impl->acceptor.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) {
    return ioError("--ws-port: cannot listen on " + impl->options.address + ":" +
                   std::to_string(impl->options.port) + ": " + ec.message());
  }
  impl->port = impl->acceptor.local_endpoint().port();
  logEvent(LogLevel::kInfo, "web_listening",
           {{"address", impl->options.address},
            {"port", static_cast<int64_t>(impl->acceptor.local_endpoint().port())},
            {"tls", impl->options.tls != nullptr},
            {"page_bytes_gzip", impl->files.transferBytes()}});
  impl->accept();
  return std::unique_ptr<WebPort>(new WebPort(std::move(impl)));
}

uint16_t WebPort::port() const {
  return impl_->port;
}

void WebPort::stop() {
  asio::post(impl_->acceptor.get_executor(), [impl = impl_] {
    impl->stopped = true;
    boost::system::error_code ignored;
    impl->acceptor.close(ignored);
  });
}

}  // namespace tessera::server
