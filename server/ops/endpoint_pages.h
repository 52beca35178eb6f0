// What the operations endpoint answers (docs/OPERATIONS.md, "Health and
// metrics"), apart from how it is served (http_endpoint.h):
//   /healthz  200 {"status":"ok","version":...,"uptime_seconds":...} while
//             serving; 503 with a "reason" while not
//   /metrics  the Prometheus text format (metrics_exposition.h)
// anything else a 404. Called from the endpoint's threads, several at once.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "server/base/server_stats.h"
#include "server/ops/metrics_exposition.h"
#include "server/store/store.h"

namespace tessera::server {

struct HttpSources {
  const ServerStats* stats = nullptr;
  std::function<store::StoreStats()> storeStats;
  std::function<int64_t()> documentsOpen;
  // Why the server is not healthy, or nullopt when it is.
  std::function<std::optional<std::string>()> unhealthy;
  store::Durability durability;  // what an acknowledged edit survives (the store says, once)
};

struct EndpointPage {
  int status = 200;
  std::string contentType;
  std::string body;
};

class EndpointPages {
 public:
  explicit EndpointPages(HttpSources sources) : sources_(std::move(sources)) {}

  // The page at `path`, a request's target without its query.
  EndpointPage get(std::string_view path);

  // Samples the edit counter for tessera_edits_per_second: the endpoint
  // calls it once a second, and every scrape does too.
  void sampleEdits();

 private:
  EndpointPage health() const;
  EndpointPage metrics();

  HttpSources sources_;
  RateWindow edits_{std::chrono::seconds(10)};
};

}  // namespace tessera::server
