#include "server/base/config.h"

#include <algorithm>
#include <thread>

namespace tessera::server {

int defaultNetworkThreads() {
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

Status checkServerConfig(const ServerConfig& c) {
  if (c.tlsCertificate.empty() != c.tlsPrivateKey.empty()) {
    return invalidArgument("--tls-cert and --tls-key go together");
  }
  if (c.limits.queueHardBytes < c.limits.queueSoftBytes) {
    return invalidArgument("--queue-hard-bytes must be at least --queue-soft-bytes");
  }
  if (c.limits.authFailureMaxDelayMs < c.limits.authFailureDelayMs) {
    return invalidArgument("--auth-failure-max-delay-ms must be at least --auth-failure-delay-ms");
  }
  if (!c.httpPortFile.empty() && c.httpPort < 0) {
    return invalidArgument("--http-port-file needs --http-port (the HTTP endpoint is off without it)");
  }
  if ((!c.wsPortFile.empty() || !c.webRoot.empty() || !c.wsAllowedOrigins.empty()) && c.wsPort < 0) {
    return invalidArgument(
        "--ws-port-file, --web-root and --ws-allowed-origin need --ws-port (the web port is off without it)");
  }
  return Status::ok();
}

}  // namespace tessera::server
