// Starts the real tessera-server binary on 127.0.0.1 with an ephemeral port
// and a real SQLite data directory, for integration tests; stops it with
// SIGTERM (or SIGKILL) and reports how it exited.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

#include "client/lib/session.h"
#include "core/util/status.h"

namespace tessera::testing {

class ServerProcess {
 public:
  // `dataDirectory` holds the store; the admin token is written beside it.
  static Expected<ServerProcess> start(const std::string& dataDirectory,
                                       const std::vector<std::string>& extraArgs = {});
  ServerProcess(ServerProcess&& other) noexcept;
  ~ServerProcess();

  uint16_t port() const { return port_; }
  pid_t pid() const { return pid_; }
  const std::string& adminToken() const { return adminToken_; }
  // SIGTERM, then wait up to 20 s: the exit code (or -signal).
  int stop();
  // SIGKILL: no goodbye, no flush.
  void kill9();
  bool running() const { return pid_ > 0; }

  client::SessionOptions session(const std::string& name, const std::string& token) const {
    return {.host = "127.0.0.1", .port = port_, .name = name, .token = token, .timeoutSeconds = 20};
  }

 private:
  ServerProcess() = default;
  pid_t pid_ = -1;
  uint16_t port_ = 0;
  std::string adminToken_;
};

}  // namespace tessera::testing
