// The operations endpoint (docs/OPERATIONS.md, "Health and metrics"): plain HTTP, off unless
// --http-port is given, on loopback unless --http-listen says otherwise.
//   GET /healthz  200 {"status":"ok",...} while serving; 503 with the reason
//                 while stopping or when the store cannot be read
//   GET /metrics  Prometheus text format (metrics_exposition.h)
// (what it answers: endpoint_pages.h). Boost.Beast, as the web port: the
// requests it reads are those of server/base/http_requests.h (8 KiB of
// headers, no body; GET and HEAD only, anything else a 405). It runs on an
// io_context and two threads of its own, so a scrape never waits behind
// documents' work, and one answer waiting for the store does not hold the
// others.
// Every connection has 5 s to send its request (and to take its answer),
// then it is closed, so slow or idle peers cannot hold the endpoint; at
// most 32 are open at once, more get a 503.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/util/status.h"
#include "server/ops/endpoint_pages.h"

namespace tessera::server {

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
