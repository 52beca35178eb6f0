// A minimal client of tessera-server's web port (--ws-port) for tests: raw
// HTTP exchanges (http_exchange.h), and the protocol over a WebSocket, one
// frame per binary message (PROTOCOL.md §1.2), written with Boost.Beast
// independently of the server's code. Blocking, with a receive timeout on
// the socket so that a silent server fails a test instead of hanging it.
#pragma once

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <memory>
#include <string>

#include "core/util/status.h"
#include "integration/http_exchange.h"
#include "protocol/framing.h"
#include "protocol/tessera.pb.h"

namespace tessera::testing {

class WebSocketClient {
 public:
  // Connects to ws://127.0.0.1:port/ws (or `path`), with `origin` as the
  // Origin header when not empty.
  static Expected<std::unique_ptr<WebSocketClient>> connect(uint16_t port, const std::string& path = "/ws",
                                                            const std::string& origin = "") {
    auto c = std::unique_ptr<WebSocketClient>(new WebSocketClient);
    boost::system::error_code ec;
    c->ws_.next_layer().connect({boost::asio::ip::make_address("127.0.0.1"), port}, ec);
    if (ec) return ioError("connect: " + ec.message());
    setReceiveTimeout(c->ws_.next_layer(), 20);
    if (!origin.empty()) {
      c->ws_.set_option(
          boost::beast::websocket::stream_base::decorator([origin](boost::beast::websocket::request_type& r) {
            r.set(boost::beast::http::field::origin, origin);
          }));
    }
    boost::beast::websocket::response_type response;
    c->ws_.handshake(response, "127.0.0.1:" + std::to_string(port), path, ec);
    if (ec)
      return ioError("WebSocket handshake: " + ec.message() + " (HTTP " +
                     std::to_string(response.result_int()) + ")");
    c->ws_.binary(true);
    return c;
  }

  Status sendBytes(const std::string& bytes, bool binary = true) {
    boost::system::error_code ec;
    ws_.binary(binary);
    ws_.write(boost::asio::buffer(bytes), ec);
    ws_.binary(true);
    return ec ? ioError("WebSocket write: " + ec.message()) : Status::ok();
  }

  Status send(const wire::ClientMessage& message) {
    TESSERA_ASSIGN_OR_RETURN(std::string frame, encodeFrame(message));
    return sendBytes(frame);
  }

  // The next message, which must be exactly one frame.
  Expected<wire::ServerMessage> receive() {
    boost::beast::flat_buffer buffer;
    boost::system::error_code ec;
    ws_.read(buffer, ec);
    if (ec) return ioError("WebSocket read: " + ec.message());
    const std::string bytes = boost::beast::buffers_to_string(buffer.data());
    FrameDecoder decoder;
    TESSERA_RETURN_IF_ERROR(decoder.feed(bytes));
    wire::ServerMessage message;
    TESSERA_ASSIGN_OR_RETURN(bool got, decoder.next(message));
    if (!got)
      return invalidArgument("a WebSocket message of " + std::to_string(bytes.size()) +
                             " bytes is not a whole frame");
    wire::ServerMessage extra;
    auto more = decoder.next(extra);
    if (more.isOk() && *more) return invalidArgument("a WebSocket message holds more than one frame");
    ++messages_;
    return message;
  }

  // Messages until one answers `clientSeq` (an Ack, Reject or reply) or is
  // an Error; the others go to `other`.
  template <typename Other>
  Expected<wire::ServerMessage> callReply(uint64_t clientSeq, Other other) {
    for (int i = 0; i < 100000; ++i) {
      TESSERA_ASSIGN_OR_RETURN(wire::ServerMessage m, receive());
      if (m.has_error()) return m;
      if ((m.has_ack() && m.ack().client_seq() == clientSeq) ||
          (m.has_reject() && m.reject().client_seq() == clientSeq) ||
          (m.has_hello_ack() && m.hello_ack().client_seq() == clientSeq)) {
        return m;
      }
      other(m);
    }
    return ioError("no reply");
  }

  uint64_t messages() const { return messages_; }

 private:
  WebSocketClient() : ws_(io_) {}
  boost::asio::io_context io_;
  boost::beast::websocket::stream<boost::asio::ip::tcp::socket> ws_;
  uint64_t messages_ = 0;
};

}  // namespace tessera::testing
