#include "server/base/http_requests.h"

#include <boost/asio/buffer.hpp>
#include <boost/asio/error.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core/error.hpp>
#include <boost/beast/http/error.hpp>
#include <boost/beast/http/field.hpp>
#include <memory>

#include "tessera/version.h"

namespace tessera::server {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;

const std::string& serverName() {
  static const std::string name = std::string("tessera-server ") + kVersion;
  return name;
}

void limitToHeaders(RequestParser& parser) {
  parser.header_limit(kRequestHeaderLimitBytes);
  parser.body_limit(0);
}

std::optional<UnreadableRequest> unreadableRequest(const beast::error_code& ec) {
  if (ec == http::error::header_limit) {
    return UnreadableRequest{
        http::status::request_header_fields_too_large,
        "request headers larger than " + std::to_string(kRequestHeaderLimitBytes) + " bytes"};
  }
  if (ec == http::error::body_limit || ec == http::error::unexpected_body) {
    return UnreadableRequest{http::status::payload_too_large, "requests to this port carry no body"};
  }
  if (ec == http::error::end_of_stream || ec == beast::error::timeout || ec == asio::error::eof ||
      ec == asio::error::operation_aborted || ec == asio::error::connection_reset) {
    return std::nullopt;
  }
  return UnreadableRequest{http::status::bad_request, "malformed request: " + ec.message()};
}

TextResponse textResponse(http::status status, const std::string& text, bool keepAlive) {
  TextResponse response(status, 11);
  serverHeaders(response);
  response.set(http::field::content_type, "text/plain; charset=utf-8");
  if (status == http::status::method_not_allowed) response.set(http::field::allow, "GET, HEAD");
  response.body() = text + "\n";
  response.prepare_payload();
  response.keep_alive(keepAlive);
  return response;
}

void closeSocket(tcp::socket& socket) {
  beast::error_code ignored;
  socket.shutdown(tcp::socket::shutdown_both, ignored);
  socket.close(ignored);
}

void turnAway(tcp::socket socket, const std::string& reason) {
  auto held = std::make_shared<tcp::socket>(std::move(socket));
  auto text = std::make_shared<std::string>(
      "HTTP/1.1 503 Service Unavailable\r\nContent-Type: text/plain\r\nConnection: close\r\n"
      "Content-Length: " +
      std::to_string(reason.size() + 1) + "\r\n\r\n" + reason + "\n");
  asio::async_write(*held, asio::buffer(*text),
                    [held, text](const boost::system::error_code&, size_t) { closeSocket(*held); });
}

}  // namespace tessera::server
