// Real nats-server processes for the cluster tests: one server, or a
// JetStream cluster of three, on 127.0.0.1 with ports picked free and data in
// a temporary directory removed at the end. Each server can be killed
// (SIGKILL), paused (SIGSTOP/SIGCONT) and started again on its own data.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "core/util/status.h"
#include "server/cluster/nats_link.h"

namespace tessera::testing {

class NatsCluster {
 public:
  // Starts `servers` nats-servers (1, or 3 for a JetStream cluster) and waits
  // until JetStream answers through every one of them.
  // `maxPayload`: the servers' max_payload (the NATS default is 1MB).
  static Expected<NatsCluster> start(int servers, const std::string& maxPayload = "8MB");
  NatsCluster(NatsCluster&& other) noexcept;
  NatsCluster& operator=(NatsCluster&&) = delete;
  ~NatsCluster();

  int size() const { return static_cast<int>(servers_.size()); }
  // "nats://127.0.0.1:P1,nats://127.0.0.1:P2,..." (every server), or one.
  std::string urls() const;
  std::string url(int server) const;
  const std::string& directory() const { return directory_; }
  // A client connection to every server, as a node makes one.
  Expected<std::unique_ptr<cluster::NatsLink>> connect() const;

  // Which server (0-based) leads `stream` now, by its server_name n1, n2...
  Expected<int> leaderOf(const std::string& stream) const;

  void kill9(int server);
  Status restart(int server);  // after kill9, on the same data and ports
  void pause(int server);      // SIGSTOP
  void resume(int server);     // SIGCONT
  // Waits until JetStream answers a request through `server` (a meta leader
  // is elected and the server is in the cluster), up to `limit`.
  Status waitForJetStream(int server, std::chrono::seconds limit = std::chrono::seconds(20)) const;

 private:
  struct Server {
    pid_t pid = -1;
    int clientPort = 0, routePort = 0;
    std::string config;
  };
  NatsCluster() = default;
  Status launch(int server);

  std::string directory_;
  std::vector<Server> servers_;
};

}  // namespace tessera::testing
