#include "server/cluster/nats_server_info.h"

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/read_until.hpp>
#include <boost/asio/streambuf.hpp>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace tessera::cluster {

namespace asio = boost::asio;

Expected<NatsServerInfo> parseNatsInfoLine(const std::string& line) {
  if (line.rfind("INFO ", 0) != 0) return unavailableError("not a NATS server: it did not begin with INFO");
  const auto json = nlohmann::json::parse(line.substr(5), nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded() || !json.is_object())
    return parseError("the NATS server's INFO is not a JSON object");
  if (!json.contains("version") || !json["version"].is_string())
    return parseError("the NATS server's INFO has no version");
  NatsServerInfo info;
  info.version = json["version"].get<std::string>();
  info.jetstream =
      json.contains("jetstream") && json["jetstream"].is_boolean() && json["jetstream"].get<bool>();
  return info;
}

Expected<NatsServerInfo> readNatsServerInfo(const std::string& url, std::chrono::milliseconds timeout) {
  const std::string prefix = "nats://";
  if (url.rfind(prefix, 0) != 0) return invalidArgument(url + ": not a nats://host:port URL");
  const std::string hostPort = url.substr(prefix.size());
  const size_t colon = hostPort.rfind(':');
  if (colon == std::string::npos) return invalidArgument(url + ": no port");
  asio::io_context io;
  asio::ip::tcp::resolver resolver(io);
  asio::ip::tcp::socket socket(io);
  asio::streambuf buffer;
  boost::system::error_code result = asio::error::timed_out;
  bool done = false;
  resolver.async_resolve(hostPort.substr(0, colon), hostPort.substr(colon + 1), [&](auto ec, auto endpoints) {
    if (ec) {
      result = ec, done = true;
      return;
    }
    asio::async_connect(socket, endpoints, [&](auto ec2, auto) {
      if (ec2) {
        result = ec2, done = true;
        return;
      }
      asio::async_read_until(socket, buffer, "\r\n", [&](auto ec3, size_t) { result = ec3, done = true; });
    });
  });
  io.run_for(timeout);
  if (!done)
    return unavailableError(url + ": no INFO from the NATS server within " + std::to_string(timeout.count()) +
                            " ms");
  if (result) return unavailableError(url + ": " + result.message());
  std::string line((std::istreambuf_iterator<char>(&buffer)), std::istreambuf_iterator<char>());
  line = line.substr(0, line.find("\r\n"));
  auto info = parseNatsInfoLine(line);
  if (!info.isOk()) return info.status().withContext(url);
  return info;
}

bool supportsPerWriteSync(const std::string& version) {
  int major = 0, minor = 0;
  if (std::sscanf(version.c_str(), "%d.%d", &major, &minor) != 2) return false;
  return major > 2 || (major == 2 && minor >= 10);
}

store::Durability natsDurability(const NatsServerInfo& info) {
  store::Durability d;
  d.backend = "nats";
  d.engineVersion = info.version;
  if (supportsPerWriteSync(info.version)) {
    d.sync = store::WriteSync::kConfigured;
    d.statement =
        "acknowledged once a majority of the NATS servers stored it; on disk at once only if they set "
        "jetstream { sync_interval: always } (nats-server " +
        info.version + " has it; a node cannot read their configuration)";
  } else {
    d.sync = store::WriteSync::kNotEachWrite;
    d.statement =
        "acknowledged once a majority of the NATS servers hold it in memory and the page cache, not yet "
        "on disk: nats-server " +
        info.version +
        " has no sync_interval (2.10 and later do), so a power loss of a majority of its machines can "
        "lose acknowledged edits";
  }
  return d;
}

}  // namespace tessera::cluster
