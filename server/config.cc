#include "server/config.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <map>
#include <thread>

namespace tessera::server {

const char* const kServerUsage =
    "usage: tessera-server [options]\n"
    "  --data DIR                 data directory (SQLite store), default tessera-data\n"
    "  --listen ADDR              address to bind, default 127.0.0.1\n"
    "  --port N                   port, default 7878; 0 picks a free one\n"
    "  --port-file PATH           write the bound port to PATH once listening\n"
    "  --admin-token-file PATH    grant the token in PATH admin rights on every document\n"
    "  --tls-cert PATH --tls-key PATH   serve TLS (PEM files)\n"
    "  --network-threads N        default: one per core\n"
    "  --worker-threads N         tessellation and encoding, default 1\n"
    "  --bulk-threads N           imports, loads and large documents' heavy commands, default 1\n"
    "  --bulk-triangles N         work estimated above N triangles is bulk, default 200000\n"
    "  --max-frame-bytes N        default 67108864\n"
    "  --max-mesh-bytes N         default 50331648\n"
    "  --max-level N              default 6\n"
    "  --max-triangles N          per subscriber, default 4000000\n"
    "  --commands-per-second X    per connection, default 200\n"
    "  --connections-per-address N  default 2000\n"
    "  --hello-max-bytes N        the first frame (the Hello), default 16384\n"
    "  --unauthenticated-per-address N  connections without a known token yet, default 64\n"
    "  --unauthenticated-total N  and over all addresses, default 512\n"
    "  --auth-failure-delay-ms X  an address's attempts after a failed token are spaced by X ms,\n"
    "                             doubling per recent failure, default 250\n"
    "  --auth-failure-max-delay-ms X  up to X ms, default 30000\n"
    "  --profiles-per-document N  distinct LOD profiles held per document, default 8\n"
    "  --subscriptions-per-session N  documents one session subscribes at once, default 16\n"
    "  --selection-max-ids N      ids in one selection, default 1024\n"
    "  --queue-soft-bytes N --queue-hard-bytes N --queue-messages N\n"
    "  --send-buffer-bytes N      kernel send buffer per connection (0: system default)\n"
    "  --idle-timeout S --write-timeout S --handshake-timeout S\n"
    "  --snapshot-every N         journal entries between snapshots, default 200\n"
    "  --delta-interval-ms X      at most one delta per document every X ms (edits between\n"
    "                             share it; acks are not delayed), default 0\n"
    "  --delta-frames-per-second N  and at most N delta frames per second per document over\n"
    "                             all its subscribers (interval = subscribers / N), default 40000\n"
    "  --deltas-after-durable     deltas also wait for their last command's journal commit\n"
    "                             (default: sent when encoded; acks always wait)\n"
    "  --verbose                  debug logs\n";

namespace {

template <typename T>
Status parseNumber(const std::string& option, const std::string& text, T minimum, T& out) {
  T value{};
  if constexpr (std::is_floating_point_v<T>) {
    char* end = nullptr;
    value = static_cast<T>(std::strtod(text.c_str(), &end));
    if (text.empty() || *end != '\0' || !std::isfinite(value)) {
      return invalidArgument(option + " expects a number, got '" + text + "'");
    }
  } else {
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || ptr != text.data() + text.size()) {
      return invalidArgument(option + " expects a whole number, got '" + text + "'");
    }
  }
  if (value < minimum) return invalidArgument(option + " must be at least " + std::to_string(minimum) + ", got " + text);
  out = value;
  return Status::ok();
}

}  // namespace

int defaultNetworkThreads() { return std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }

Expected<ServerConfig> parseServerArguments(const std::vector<std::string>& args) {
  ServerConfig c;
  using Setter = std::function<Status(const std::string&, const std::string&)>;
  auto text = [](std::string& field) -> Setter {
    return [&field](const std::string&, const std::string& v) {
      field = v;
      return Status::ok();
    };
  };
  auto number = [](auto& field, auto minimum) -> Setter {
    return [&field, minimum](const std::string& o, const std::string& v) {
      return parseNumber(o, v, static_cast<std::decay_t<decltype(field)>>(minimum), field);
    };
  };
  const std::map<std::string, Setter> options = {
      {"--data", text(c.dataDirectory)},
      {"--listen", text(c.listenAddress)},
      {"--port", number(c.port, 0)},
      {"--port-file", text(c.portFile)},
      {"--admin-token-file", text(c.adminTokenFile)},
      {"--tls-cert", text(c.tlsCertificate)},
      {"--tls-key", text(c.tlsPrivateKey)},
      {"--network-threads", number(c.networkThreads, 1)},
      {"--worker-threads", number(c.workerThreads, 1)},
      {"--bulk-threads", number(c.bulkThreads, 1)},
      {"--bulk-triangles", number(c.bulkTriangles, 0)},
      {"--hello-max-bytes", number(c.limits.helloMaxBytes, 256)},
      {"--unauthenticated-per-address", number(c.limits.unauthenticatedPerAddress, 1)},
      {"--unauthenticated-total", number(c.limits.unauthenticatedTotal, 1)},
      {"--auth-failure-delay-ms", number(c.limits.authFailureDelayMs, 0.0)},
      {"--auth-failure-max-delay-ms", number(c.limits.authFailureMaxDelayMs, 0.0)},
      {"--profiles-per-document", number(c.limits.profilesPerDocument, 1)},
      {"--subscriptions-per-session", number(c.limits.subscriptionsPerSession, 1)},
      {"--selection-max-ids", number(c.limits.selectionMaxIds, 0)},
      {"--max-frame-bytes", number(c.limits.maxFrameBytes, 1024)},
      {"--max-mesh-bytes", number(c.limits.maxBaseMeshBytes, 1)},
      {"--max-level", number(c.limits.maxLevel, 0)},
      {"--max-triangles", number(c.limits.maxTrianglesPerSubscriber, 1)},
      {"--commands-per-second", number(c.limits.commandsPerSecond, 0.001)},
      {"--connections-per-address", number(c.limits.connectionsPerAddress, 1)},
      {"--queue-soft-bytes", number(c.limits.queueSoftBytes, 1024)},
      {"--queue-hard-bytes", number(c.limits.queueHardBytes, 1024)},
      {"--queue-messages", number(c.limits.queueMaxMessages, 4)},
      {"--send-buffer-bytes", number(c.limits.sendBufferBytes, 0)},
      {"--idle-timeout", number(c.timeouts.idleSeconds, 0.01)},
      {"--write-timeout", number(c.timeouts.writeSeconds, 0.01)},
      {"--handshake-timeout", number(c.timeouts.handshakeSeconds, 0.01)},
      {"--snapshot-every", number(c.snapshotEvery, 1)},
      {"--delta-interval-ms", number(c.deltaIntervalMs, 0.0)},
      {"--delta-frames-per-second", number(c.deltaFramesPerSecond, 0.0)},
  };
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--verbose") {
      c.verbose = true;
      continue;
    }
    if (args[i] == "--deltas-after-durable") {
      c.deltasAfterDurable = true;
      continue;
    }
    auto it = options.find(args[i]);
    if (it == options.end()) return invalidArgument("unknown option '" + args[i] + "'");
    if (i + 1 >= args.size()) return invalidArgument(args[i] + " needs a value");
    TESSERA_RETURN_IF_ERROR(it->second(args[i], args[i + 1]));
    ++i;
  }
  if (c.tlsCertificate.empty() != c.tlsPrivateKey.empty()) {
    return invalidArgument("--tls-cert and --tls-key go together");
  }
  if (c.limits.queueHardBytes < c.limits.queueSoftBytes) {
    return invalidArgument("--queue-hard-bytes must be at least --queue-soft-bytes");
  }
  return c;
}

}  // namespace tessera::server
