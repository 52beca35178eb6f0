// What a NATS server says of itself when a client connects: the INFO line
// it sends first (NATS client protocol, "INFO"), read over a plain TCP
// connection. A cluster node reads the servers' version at start, to say
// which guarantee its acknowledgements carry (docs/CLUSTER.md "What an
// acknowledged edit survives"): JetStream syncs each write to disk before
// acknowledging only with sync_interval: always, which nats-server has from
// 2.10 on; 2.9 refuses the option.
#pragma once

#include <chrono>
#include <string>

#include "core/util/status.h"
#include "server/store/store.h"

namespace tessera::cluster {

struct NatsServerInfo {
  std::string version;  // "2.9.10"
  bool jetstream = false;
};

// Connects to nats://host:port and reads its INFO line. Errors name the URL:
// no answer in `timeout`, not a NATS server, an INFO without a version.
Expected<NatsServerInfo> readNatsServerInfo(const std::string& url, std::chrono::milliseconds timeout);

// The INFO line itself ("INFO {...}"), parsed: the same errors.
Expected<NatsServerInfo> parseNatsInfoLine(const std::string& line);

// Whether a version string is 2.10 or later (per-write sync possible).
bool supportsPerWriteSync(const std::string& version);

// The durability a node on such servers runs with.
store::Durability natsDurability(const NatsServerInfo& info);

}  // namespace tessera::cluster
