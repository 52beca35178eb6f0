#include "server/ops/http_get.h"

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <optional>

#include "server/base/http_requests.h"

namespace tessera::server {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;

namespace {

constexpr uint64_t kReplyLimitBytes = 1 << 20;  // far above a /healthz or a /metrics page

struct HttpUrl {
  std::string host;      // without brackets, for the resolver
  std::string port;      // "80" unless the URL gives one
  std::string hostPort;  // the Host header
  std::string target;    // "/" at least
};

Expected<HttpUrl> parseHttpUrl(const std::string& url) {
  const std::string scheme = "http://";
  const Status malformed = invalidArgument("expected http://HOST[:PORT][/PATH], got '" + url + "'");
  if (url.compare(0, scheme.size(), scheme) != 0) return malformed;
  const size_t slash = url.find('/', scheme.size());
  HttpUrl parsed;
  parsed.hostPort =
      url.substr(scheme.size(), slash == std::string::npos ? std::string::npos : slash - scheme.size());
  parsed.target = slash == std::string::npos ? "/" : url.substr(slash);
  const std::string& authority = parsed.hostPort;
  size_t hostEnd = 0;
  if (!authority.empty() && authority[0] == '[') {
    hostEnd = authority.find(']');
    if (hostEnd == std::string::npos) return malformed;
    parsed.host = authority.substr(1, hostEnd - 1);
    ++hostEnd;
  } else {
    hostEnd = authority.find(':');
    if (hostEnd == std::string::npos) hostEnd = authority.size();
    parsed.host = authority.substr(0, hostEnd);
  }
  if (parsed.host.empty()) return malformed;
  if (hostEnd == authority.size()) {
    parsed.port = "80";
  } else if (authority[hostEnd] == ':' && hostEnd + 1 < authority.size() &&
             authority.find_first_not_of("0123456789", hostEnd + 1) == std::string::npos) {
    parsed.port = authority.substr(hostEnd + 1);
  } else {
    return malformed;
  }
  return parsed;
}

}  // namespace

Expected<HttpReply> httpGet(const std::string& url, std::chrono::milliseconds timeout) {
  auto where = parseHttpUrl(url);
  if (!where.isOk()) return where.status();
  asio::io_context io;
  tcp::resolver resolver(io);
  beast::tcp_stream stream(io);
  beast::flat_buffer buffer;
  http::request<http::empty_body> request(http::verb::get, where->target, 11);
  request.set(http::field::host, where->hostPort);
  request.set(http::field::user_agent, serverName());
  request.keep_alive(false);
  http::response_parser<http::string_body> parser;
  parser.body_limit(kReplyLimitBytes);

  // Each step starts the next from its handler; the first to fail says
  // where. run_for bounds them all, name resolution included.
  std::optional<Status> failure;
  bool answered = false;
  auto fail = [&](const std::string& step, const beast::error_code& ec) {
    failure = ioError("GET " + url + ": " + step + ": " + ec.message());
  };
  resolver.async_resolve(
      where->host, where->port,
      [&](const beast::error_code& resolved, const tcp::resolver::results_type& found) {
        if (resolved) return fail("cannot resolve " + where->host, resolved);
        stream.async_connect(found, [&](const beast::error_code& connected, const tcp::endpoint&) {
          if (connected) return fail("cannot connect", connected);
          http::async_write(stream, request, [&](const beast::error_code& sent, size_t) {
            if (sent) return fail("cannot send the request", sent);
            http::async_read(stream, buffer, parser, [&](const beast::error_code& read, size_t) {
              if (read) return fail("no valid answer", read);
              answered = true;
            });
          });
        });
      });
  io.run_for(timeout);
  if (failure) return *failure;
  if (!answered) {
    return timeoutError("GET " + url + ": no answer within " + std::to_string(timeout.count()) + " ms");
  }
  const auto& response = parser.get();
  HttpReply reply;
  reply.status = static_cast<int>(response.result_int());
  const auto contentType = response[http::field::content_type];
  reply.contentType.assign(contentType.data(), contentType.size());
  reply.body = response.body();
  return reply;
}

}  // namespace tessera::server
