// tessera-server: the acceptor, the network threads, the worker pool for
// document strands, the store, and graceful shutdown on SIGTERM/SIGINT:
// stop accepting, make pending journal writes durable (their acks go out),
// tell every client, close.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/asio/strand.hpp>
#include <boost/asio/thread_pool.hpp>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include <atomic>
#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/steady_timer.hpp>

#include "server/base/config.h"
#include "server/document/document_registry.h"
#include "server/net/auth_throttle.h"
#include "server/net/connection.h"
#include "server/net/server_context.h"
#include "server/net/web_port.h"
#include "server/ops/http_endpoint.h"
#include "server/store/store.h"

namespace tessera::cluster {
class ClusterNode;
}  // namespace tessera::cluster

namespace tessera::server {

// The store `config` names: the SQLite one of --data, or, with --cluster,
// the NATS JetStream one shared by every node of the cluster.
Expected<std::unique_ptr<store::Store>> openStore(const ServerConfig& config);
// --node-name, or the host name.
std::string nodeNameOf(const ServerConfig& config);

class Server {
 public:
  static Expected<std::unique_ptr<Server>> create(const ServerConfig& config);
  ~Server();

  uint16_t port() const { return port_; }
  // The HTTP endpoint's port, 0 when it is off.
  uint16_t httpPort() const { return http_ ? http_->port() : 0; }
  // The web port's (--ws-port), 0 when it is off.
  uint16_t webPort() const { return web_ ? web_->port() : 0; }
  // Serves until a signal or stop(); returns once everything is closed.
  void run();
  void stop();

 private:
  explicit Server(const ServerConfig& config);
  void accept();
  // Adds a connection on `transport` unless the limits refuse it (on strand_).
  void admit(std::shared_ptr<PendingUpgrade> upgrade);
  Status startWebPort();
  void shutdown();
  void stopBulk();
  void awaitHangup();   // SIGHUP: reopen the log file (logrotate)
  void pingWatchdog();  // systemd's WatchdogSec, when the unit sets it
  std::optional<std::string> unhealthy();
  // Whether a new connection from `address` stays within the connection
  // limits; otherwise why not.
  std::optional<std::string> overLimits(const std::string& address);
  // overLimits, with a refusal logged and counted.
  std::optional<std::string> admission(const std::string& address);
  // A Connection on `transport`: refused at once with `refusal`, or
  // registered and served.
  void startConnection(std::unique_ptr<Transport> transport, ConnectionStrand strand,
                       const std::string& address, const std::optional<std::string>& refusal);

  ServerConfig config_;
  boost::asio::io_context io_;
  // Accepting, signals and shutdown share connections_: one strand, whatever
  // the number of network threads.
  boost::asio::strand<boost::asio::io_context::executor_type> strand_;
  boost::asio::thread_pool workers_;
  // Bulk work (docs/ARCHITECTURE.md, "Bulk work") on threads of their own at a lower CPU priority.
  boost::asio::io_context bulkIo_;
  std::optional<boost::asio::executor_work_guard<boost::asio::io_context::executor_type>> bulkWork_;
  std::vector<std::thread> bulkThreads_;
  AuthThrottle authThrottle_;
  boost::asio::ip::tcp::acceptor acceptor_;
  boost::asio::signal_set signals_;
  boost::asio::signal_set hangup_;
  boost::asio::steady_timer watchdog_;
  std::unique_ptr<store::Store> store_;
  std::unique_ptr<boost::asio::ssl::context> tls_;
  ServerStats stats_;
  std::unique_ptr<DocumentRegistry> registry_;
  std::unique_ptr<cluster::ClusterNode> cluster_;  // cluster mode only; after registry_, before context_
  std::unique_ptr<ServerContext> context_;
  uint16_t port_ = 0;
  uint64_t nextSession_ = 1;
  bool stopping_ = false;
  std::atomic<bool> serving_{false};  // for /healthz, read from the HTTP threads
  std::unique_ptr<WebPort> web_;
  std::unique_ptr<HttpEndpoint> http_;  // declared last: stopped before what it reads
  std::map<uint64_t, std::weak_ptr<Connection>> connections_;
};

}  // namespace tessera::server
