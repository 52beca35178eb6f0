// HTTP on loopback for tests of tessera-server's two HTTP ports, the web
// port (--ws-port) and the operations endpoint (--http-port): raw
// exchanges, for requests no proper client would send, and a plain GET.
// Written with Boost.Beast independently of the server's code. Blocking,
// with a receive timeout on the socket so that a silent server fails a
// test instead of hanging it.
#pragma once

#include <sys/socket.h>
#include <sys/time.h>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <string>

#include "core/util/status.h"

namespace tessera::testing {

inline void setReceiveTimeout(boost::asio::ip::tcp::socket& socket, int seconds) {
  timeval tv{seconds, 0};
  setsockopt(socket.native_handle(), SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
}

// Sends `request` as it is and returns everything the server sends until
// it closes (or the timeout).
inline std::string httpExchange(uint16_t port, const std::string& request, int timeoutSeconds = 10) {
  namespace asio = boost::asio;
  asio::io_context io;
  asio::ip::tcp::socket socket(io);
  boost::system::error_code ec;
  socket.connect({asio::ip::make_address("127.0.0.1"), port}, ec);
  if (ec) return "connect failed: " + ec.message();
  setReceiveTimeout(socket, timeoutSeconds);
  asio::write(socket, asio::buffer(request), ec);
  std::string response;
  char buffer[65536];
  while (true) {
    const size_t n = socket.read_some(asio::buffer(buffer), ec);
    response.append(buffer, n);
    if (ec) break;
  }
  return response;
}

// The status code of an HTTP response, or 0.
inline int httpStatus(const std::string& response) {
  if (response.rfind("HTTP/1.1 ", 0) != 0 || response.size() < 12) return 0;
  return std::stoi(response.substr(9, 3));
}

struct HttpReply {
  int status = 0;
  std::string contentType;
  std::string body;
};

// GET http://127.0.0.1:port`target` on a connection of its own: the whole
// answer, or why there is none (refused, reset, no answer within
// `timeoutSeconds`).
inline Expected<HttpReply> httpGet(uint16_t port, const std::string& target, int timeoutSeconds = 10) {
  namespace asio = boost::asio;
  namespace http = boost::beast::http;
  const std::string where = "GET 127.0.0.1:" + std::to_string(port) + target;
  asio::io_context io;
  asio::ip::tcp::socket socket(io);
  boost::system::error_code ec;
  socket.connect({asio::ip::make_address("127.0.0.1"), port}, ec);
  if (ec) return ioError(where + ": connect: " + ec.message());
  setReceiveTimeout(socket, timeoutSeconds);
  http::request<http::empty_body> request(http::verb::get, target, 11);
  request.set(http::field::host, "127.0.0.1:" + std::to_string(port));
  request.keep_alive(false);
  http::write(socket, request, ec);
  if (ec) return ioError(where + ": write: " + ec.message());
  boost::beast::flat_buffer buffer;
  http::response<http::string_body> response;
  http::read(socket, buffer, response, ec);
  if (ec) return ioError(where + ": read: " + ec.message());
  HttpReply reply;
  reply.status = static_cast<int>(response.result_int());
  const auto contentType = response[http::field::content_type];
  reply.contentType.assign(contentType.data(), contentType.size());
  reply.body = response.body();
  return reply;
}

}  // namespace tessera::testing
