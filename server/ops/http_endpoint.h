// The operations endpoint (docs/OPERATIONS.md, "Health and metrics"): plain HTTP, off unless
// --http-port is given, on loopback unless --http-listen says otherwise.
//   GET /healthz  200 {"status":"ok",...} while serving; 503 with the reason
//                 while stopping or when the store cannot be read
//   GET /metrics  Prometheus text format (metrics_exposition.h)
// It runs on two threads of its own, so a scrape never waits behind
// documents' work, and accepts nothing but small GETs.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "core/util/status.h"
#include "server/base/server_stats.h"
#include "server/store/store.h"

namespace tessera::server {

struct HttpSources {
  const ServerStats* stats = nullptr;
  std::function<store::StoreStats()> storeStats;
  std::function<int64_t()> documentsOpen;
  // Why the server is not healthy, or nullopt when it is.
  std::function<std::optional<std::string>()> unhealthy;
};

class HttpEndpoint {
 public:
  // Binds at once (so a taken port fails start-up), then serves.
  static Expected<std::unique_ptr<HttpEndpoint>> start(const std::string& address, int port,
                                                       HttpSources sources);
  ~HttpEndpoint();  // stops serving and joins its threads

  uint16_t port() const { return port_; }

 private:
  struct Impl;
  explicit HttpEndpoint(std::unique_ptr<Impl> impl, uint16_t port);
  std::unique_ptr<Impl> impl_;
  uint16_t port_;
};

}  // namespace tessera::server
