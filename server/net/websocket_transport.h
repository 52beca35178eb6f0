// The protocol over WebSocket (docs/PROTOCOL.md §1.2): one frame
// per binary message, on --ws-port, plain or TLS. The HTTP request that
// asked for the upgrade was read by the web port (web_port.h); the
// transport's start() answers it.
#pragma once

#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/ssl/ssl_stream.hpp>
#include <memory>

#include "server/net/transport.h"

namespace tessera::server {

using WebRequest = boost::beast::http::request<boost::beast::http::empty_body>;

struct WebSocketLimits {
  // The largest message a peer may send: a frame's prefix and payload. The
  // frame decoder refuses a larger prefix first, with the protocol's error;
  // this only stops the WebSocket layer from buffering more.
  uint64_t maxMessageBytes = 0;
  double handshakeSeconds = 10;  // the upgrade's answer
};

std::unique_ptr<Transport> makeWebSocketTransport(boost::beast::tcp_stream stream, WebRequest request,
                                                  const ConnectionStrand& strand, WebSocketLimits limits);
std::unique_ptr<Transport> makeWebSocketTransport(boost::beast::ssl_stream<boost::beast::tcp_stream> stream,
                                                  WebRequest request, const ConnectionStrand& strand,
                                                  WebSocketLimits limits);

}  // namespace tessera::server
