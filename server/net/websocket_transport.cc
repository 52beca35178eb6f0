#include "server/net/websocket_transport.h"

#include <array>
#include <boost/asio/dispatch.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core/buffers_range.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>

#include "protocol/message_framing.h"
#include "tessera/version.h"

namespace tessera::server {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;

namespace {

// Beast 1.74 cannot track work on a strand<any_io_executor> bound to its
// handlers (its saved_handler wants the old executor interface), so each
// completion runs on the socket's executor and is dispatched to the
// Connection's strand from there.
template <typename Next>
class WebSocketTransport final : public Transport {
 public:
  WebSocketTransport(Next stream, WebRequest request, const ConnectionStrand& strand, WebSocketLimits limits,
                     bool tls)
      : strand_(strand), tls_(tls), request_(std::move(request)), ws_(std::move(stream)) {
    // The Connection keeps the protocol's deadlines (handshake, idle,
    // write); the WebSocket layer's own apply only to its handshake and
    // closing.
    beast::get_lowest_layer(ws_).expires_never();
    websocket::stream_base::timeout timeouts =
        websocket::stream_base::timeout::suggested(beast::role_type::server);
    timeouts.handshake_timeout = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(limits.handshakeSeconds));
    ws_.set_option(timeouts);
    ws_.set_option(websocket::stream_base::decorator([](websocket::response_type& response) {
      response.set(beast::http::field::server, std::string("tessera-server ") + kVersion);
    }));
    ws_.read_message_max(limits.maxMessageBytes);
    ws_.binary(true);
    ws_.auto_fragment(false);
  }

  bool needsHandshake() const override { return true; }

  void start(Done done) override {
    ws_.async_accept(request_,
                     [strand = strand_, done = std::move(done)](const boost::system::error_code& ec) {
                       asio::dispatch(strand, [done, ec] { done(ec); });
                     });
  }

  void read(Read done) override {
    ws_.async_read_some(asio::buffer(buffer_),
                        [this, done = std::move(done)](const boost::system::error_code& ec, size_t n) {
                          // Read on the socket's executor; the message state is read here,
                          // before another read can change it.
                          Status framing = ec ? Status::ok()
                                              : framing_.feed(std::string_view(buffer_.data(), n),
                                                              ws_.is_message_done(), ws_.got_binary());
                          // A text message's bytes are not frames at all: none are passed on.
                          const size_t passed = ec || !ws_.got_binary() ? 0 : n;
                          asio::dispatch(strand_, [this, done, ec, passed, framing = std::move(framing)] {
                            done(ec, std::string_view(buffer_.data(), passed), framing);
                          });
                        });
  }

  void write(std::vector<std::shared_ptr<const std::string>> frames, Written done) override {
    frames_ = std::move(frames);
    next_ = 0;
    written_ = 0;
    writeNext(std::move(done));
  }

  void close() override {
    boost::system::error_code ignored;
    auto& socket = beast::get_lowest_layer(ws_).socket();
    socket.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
    socket.close(ignored);
  }

  const char* kind() const override { return tls_ ? "wss" : "ws"; }

 private:
  // One message per frame, in order.
  void writeNext(Written done) {
    if (next_ == frames_.size()) {
      frames_.clear();
      return done({}, written_);
    }
    const auto& frame = frames_[next_];
    ws_.async_write(asio::buffer(*frame),
                    [this, done = std::move(done)](const boost::system::error_code& ec, size_t n) mutable {
                      asio::dispatch(strand_, [this, done = std::move(done), ec, n]() mutable {
                        if (ec) {
                          frames_.clear();
                          return done(ec, written_);
                        }
                        written_ += n;
                        ++next_;
                        writeNext(std::move(done));
                      });
                    });
  }

  ConnectionStrand strand_;
  bool tls_;
  WebRequest request_;
  websocket::stream<Next> ws_;
  MessageFraming framing_;
  std::array<char, 64 * 1024> buffer_{};
  std::vector<std::shared_ptr<const std::string>> frames_;  // of the write in flight
  size_t next_ = 0;
  size_t written_ = 0;
};

}  // namespace

std::unique_ptr<Transport> makeWebSocketTransport(beast::tcp_stream stream, WebRequest request,
                                                  const ConnectionStrand& strand, WebSocketLimits limits) {
  return std::make_unique<WebSocketTransport<beast::tcp_stream>>(std::move(stream), std::move(request),
                                                                 strand, limits, false);
}

std::unique_ptr<Transport> makeWebSocketTransport(beast::ssl_stream<beast::tcp_stream> stream,
                                                  WebRequest request, const ConnectionStrand& strand,
                                                  WebSocketLimits limits) {
  return std::make_unique<WebSocketTransport<beast::ssl_stream<beast::tcp_stream>>>(
      std::move(stream), std::move(request), strand, limits, true);
}

}  // namespace tessera::server
