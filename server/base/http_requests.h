// What the server's two HTTP ports share (Boost.Beast, the one HTTP stack):
// the web port (server/net/web_port.h, docs/WEB_VIEWER.md "Serving it") and
// the operations endpoint (server/ops/http_endpoint.h, docs/OPERATIONS.md
// "Health and metrics"). Both read small requests only: a start line and
// at most 8 KiB of headers, never a body. What cannot be read as such gets
// a plain-text 4xx and the connection closes; a peer that left or ran out
// of time is closed without a word.
#pragma once

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core/error.hpp>
#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/parser.hpp>
#include <boost/beast/http/status.hpp>
#include <boost/beast/http/string_body.hpp>
#include <cstdint>
#include <optional>
#include <string>

namespace tessera::server {

inline constexpr uint32_t kRequestHeaderLimitBytes = 8 * 1024;  // a request's start line and headers
inline constexpr int kRequestsPerConnection = 100;              // keep-alive, then close

using RequestParser = boost::beast::http::request_parser<boost::beast::http::empty_body>;
using TextResponse = boost::beast::http::response<boost::beast::http::string_body>;

// Sets a fresh parser's limits: kRequestHeaderLimitBytes of headers, no body.
void limitToHeaders(RequestParser& parser);

// The answer to a request that could not be read (too large, a body,
// malformed), or nullopt when there is nobody to answer: the peer closed,
// reset or timed out, or the port is closing.
struct UnreadableRequest {
  boost::beast::http::status status;
  std::string reason;
};
std::optional<UnreadableRequest> unreadableRequest(const boost::beast::error_code& ec);

// "tessera-server VERSION", the Server header of every answer.
const std::string& serverName();

// The headers every answer of either port carries: this server's name, and
// no content sniffing.
template <class Body>
void serverHeaders(boost::beast::http::response<Body>& response) {
  response.set(boost::beast::http::field::server, serverName());
  response.set("X-Content-Type-Options", "nosniff");
}

// A plain-text answer with this server's name; a 405 lists GET and HEAD as
// the methods allowed (the only ones either port serves).
TextResponse textResponse(boost::beast::http::status status, const std::string& text, bool keepAlive);

// Shuts the socket down and closes it; errors are ignored (the peer may be
// gone already).
void closeSocket(boost::asio::ip::tcp::socket& socket);

// A peer over a connection limit gets a plain 503 with `reason`, then the
// connection closes; nothing of its request is read.
void turnAway(boost::asio::ip::tcp::socket socket, const std::string& reason);

}  // namespace tessera::server
