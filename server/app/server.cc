#include "server/app/server.h"

#include <filesystem>

#include <sys/resource.h>
#include <systemd/sd-daemon.h>
#include <unistd.h>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <fstream>
#include <thread>

#include "server/base/log.h"
#include "server/cluster/cluster_node.h"
#include "server/cluster/nats_store.h"
#include "server/store/sqlite_store.h"

namespace tessera::server {

namespace asio = boost::asio;
using asio::ip::tcp;

Server::Server(const ServerConfig& config)
    : config_(config),
      strand_(asio::make_strand(io_)),
      workers_(static_cast<size_t>(config.workerThreads)),
      bulkWork_(boost::asio::make_work_guard(bulkIo_)),
      authThrottle_(AuthThrottleOptions{
          .baseDelay = std::chrono::milliseconds(static_cast<int64_t>(config.limits.authFailureDelayMs)),
          .maxDelay = std::chrono::milliseconds(static_cast<int64_t>(config.limits.authFailureMaxDelayMs))}),
      acceptor_(strand_),
      signals_(strand_, SIGINT, SIGTERM),
      hangup_(strand_, SIGHUP),
      watchdog_(strand_) {
  for (int i = 0; i < config.bulkThreads; ++i) {
    bulkThreads_.emplace_back([this] {
      // Nice 10 for this thread only (Linux threads have their own nice
      // value): when bulk and interactive work compete for the cores, the
      // scheduler favours edits and deltas.
      ::setpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()), 10);
      bulkIo_.run();
    });
  }
}

Server::~Server() {
  stopBulk();
  workers_.join();
}

void Server::stopBulk() {
  bulkWork_.reset();
  for (auto& t : bulkThreads_) t.join();
  bulkThreads_.clear();
}

namespace {

// Written under a temporary name and renamed, so a reader polling the file
// never sees it half written.
void writePortFile(const std::string& path, uint16_t port) {
  const std::string temporary = path + ".tmp";
  std::ofstream(temporary) << port << "\n";
  std::rename(temporary.c_str(), path.c_str());
}

}  // namespace

Expected<std::unique_ptr<store::Store>> openStore(const ServerConfig& config) {
  if (config.cluster.empty()) {
    TESSERA_ASSIGN_OR_RETURN(auto store, store::SqliteStore::open(config.dataDirectory));
    return std::unique_ptr<store::Store>(std::move(store));
  }
  cluster::NatsStoreOptions options;
  TESSERA_ASSIGN_OR_RETURN(options.link.urls, cluster::parseNatsUrls(config.cluster));
  options.link.clientName = "tessera-server " + nodeNameOf(config);
  options.replicas = config.clusterReplicas;
  // A NATS cluster that has just started answers JetStream requests only
  // once it elected its leaders: nodes started with it wait (up to 60 s).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (true) {
    auto store = cluster::NatsStore::open(options);
    if (store.isOk()) return std::unique_ptr<store::Store>(std::move(*store));
    if (!isTransient(store.status()) || std::chrono::steady_clock::now() > deadline) return store.status();
    logEvent(LogLevel::kWarn, "cluster_waiting", {{"error", store.status().message()}});
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
}

std::string nodeNameOf(const ServerConfig& config) {
  if (!config.nodeName.empty()) return config.nodeName;
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) != 0 || host[0] == '\0') return "tessera";
  return host;
}

Expected<std::unique_ptr<Server>> Server::create(const ServerConfig& config) {
  std::unique_ptr<Server> server(new Server(config));
  TESSERA_ASSIGN_OR_RETURN(server->store_, openStore(config));
  const store::Durability durability = server->store_->durability();
  logEvent(LogLevel::kInfo, "store_durability",
           {{"backend", durability.backend},
            {"engine_version", durability.engineVersion},
            {"write_sync", store::writeSyncName(durability.sync)},
            {"statement", durability.statement}});
  if (config.requireFsync && durability.sync == store::WriteSync::kNotEachWrite) {
    return unsupported("--require-fsync: " + durability.statement +
                       ". Install nats-server 2.10 or later on every NATS machine and set jetstream { "
                       "sync_interval: always }, or run without --cluster (SQLite fsyncs each write)");
  }
  if (config.requireFsync && durability.sync == store::WriteSync::kConfigured) {
    logEvent(LogLevel::kWarn, "require_fsync_unverified",
             {{"statement",
               "--require-fsync relies on the NATS servers setting jetstream { sync_interval: always }, "
               "which a node cannot read"}});
  }
  if (!config.adminTokenFile.empty()) {
    std::ifstream in(config.adminTokenFile);
    std::string token;
    std::getline(in, token);
    if (token.empty()) return invalidArgument(config.adminTokenFile + ": no admin token in the file");
    TESSERA_RETURN_IF_ERROR(
        server->store_->addToken(store::TokenScope::allDocuments(), token, store::Role::kAdmin));
  }
  if (!config.tlsCertificate.empty()) {
    auto tls = std::make_unique<asio::ssl::context>(asio::ssl::context::tls_server);
    boost::system::error_code ec;
    tls->set_options(asio::ssl::context::default_workarounds | asio::ssl::context::no_sslv2 |
                     asio::ssl::context::no_sslv3 | asio::ssl::context::no_tlsv1 |
                     asio::ssl::context::no_tlsv1_1);
    tls->use_certificate_chain_file(config.tlsCertificate, ec);
    if (ec) return invalidArgument("--tls-cert " + config.tlsCertificate + ": " + ec.message());
    tls->use_private_key_file(config.tlsPrivateKey, asio::ssl::context::pem, ec);
    if (ec) return invalidArgument("--tls-key " + config.tlsPrivateKey + ": " + ec.message());
    server->tls_ = std::move(tls);
  }
  server->registry_ =
      std::make_unique<DocumentRegistry>(*server->store_, server->workers_.get_executor(),
                                         server->bulkIo_.get_executor(), server->config_, server->stats_);
  DocumentOpener* opener = server->registry_.get();
  if (!config.cluster.empty()) {
    server->config_.nodeName = nodeNameOf(config);
    auto* nats = dynamic_cast<cluster::NatsStore*>(server->store_.get());
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (true) {
      auto node =
          cluster::ClusterNode::start(nats->link(), *server->store_, *server->registry_, server->config_,
                                      server->stats_, server->workers_.get_executor());
      if (node.isOk()) {
        server->cluster_ = std::move(*node);
        break;
      }
      if (!isTransient(node.status()) || std::chrono::steady_clock::now() > deadline) {
        return node.status();
      }
      logEvent(LogLevel::kWarn, "cluster_waiting", {{"error", node.status().message()}});
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
    opener = server->cluster_.get();
    server->nextSession_ = server->cluster_->firstSessionId() + 1;
  }
  server->context_ = std::make_unique<ServerContext>(
      ServerContext{server->config_, *server->store_, *opener, server->stats_,
                    server->workers_.get_executor(), server->bulkIo_.get_executor(), server->authThrottle_});
  boost::system::error_code ec;
  const auto address = asio::ip::make_address(config.listenAddress, ec);
  if (ec) return invalidArgument("--listen: bad address '" + config.listenAddress + "'");
  const tcp::endpoint endpoint(address, config.port);
  server->acceptor_.open(endpoint.protocol(), ec);
  if (!ec) server->acceptor_.set_option(tcp::acceptor::reuse_address(true), ec);
  if (!ec) server->acceptor_.bind(endpoint, ec);
  if (!ec) server->acceptor_.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) {
    return ioError("cannot listen on " + config.listenAddress + ":" + std::to_string(config.port) + ": " +
                   ec.message());
  }
  server->port_ = server->acceptor_.local_endpoint().port();
  if (config.wsPort >= 0) TESSERA_RETURN_IF_ERROR(server->startWebPort());
  if (config.httpPort >= 0) {
    Server* raw = server.get();
    TESSERA_ASSIGN_OR_RETURN(
        server->http_, HttpEndpoint::start(config.httpListenAddress, config.httpPort,
                                           HttpSources{&raw->stats_, [raw] { return raw->store_->stats(); },
                                                       [raw] { return raw->registry_->openCount(); },
                                                       [raw] { return raw->unhealthy(); }, durability}));
    if (!config.httpPortFile.empty()) {
      writePortFile(config.httpPortFile, server->http_->port());
    }
  }
  // Last: scripts and tests take the port file as the sign that every
  // port (the web and HTTP ones too) is bound.
  if (!config.portFile.empty()) {
    writePortFile(config.portFile, server->port_);
  }
  return server;
}

namespace {

// The web viewer's files when --web-root is not given: the build's own
// web/ while that build tree exists, else where `cmake --install` puts them
// beside the binary (PREFIX/bin/tessera-server, PREFIX/share/tessera/web).
std::string defaultWebRoot() {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(fs::path(TESSERA_WEB_ROOT) / "index.html", ec)) return TESSERA_WEB_ROOT;
  const fs::path binary = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return TESSERA_WEB_ROOT;
  return (binary.parent_path().parent_path() / "share" / "tessera" / "web").string();
}

}  // namespace

Status Server::startWebPort() {
  const std::string root = config_.webRoot.empty() ? defaultWebRoot() : config_.webRoot;
  TESSERA_ASSIGN_OR_RETURN(StaticFiles files, StaticFiles::load(root));
  WebPortOptions options{config_.listenAddress,    config_.wsPort, tls_.get(),
                         config_.wsAllowedOrigins, config_.limits, config_.timeouts};
  TESSERA_ASSIGN_OR_RETURN(web_, WebPort::start(io_, std::move(options), std::move(files),
                                                [this](std::shared_ptr<PendingUpgrade> upgrade) {
                                                  asio::post(strand_, [this, upgrade] { admit(upgrade); });
                                                }));
  if (!config_.wsPortFile.empty()) writePortFile(config_.wsPortFile, web_->port());
  return Status::ok();
}

// A WebSocket upgrade becomes a connection like one of the
// protocol port, within the same limits; a refusal is an HTTP 503 before
// the upgrade, since the peer speaks no frames yet.
void Server::admit(std::shared_ptr<PendingUpgrade> upgrade) {
  if (stopping_) return upgrade->refuse("the server is stopping");
  const std::string address = upgrade->address();
  // Refused before the upgrade, as an HTTP 503 the browser can show.
  if (const auto over = admission(address)) return upgrade->refuse(*over);
  ConnectionStrand strand = asio::make_strand(upgrade->executor());
  auto transport = upgrade->accept(strand);
  startConnection(std::move(transport), std::move(strand), address, std::nullopt);
}

std::optional<std::string> Server::admission(const std::string& address) {
  auto over = overLimits(address);
  if (over) {
    logEvent(LogLevel::kWarn, "connection_refused", {{"address", address}, {"reason", *over}});
    ++stats_.connectionsRefused;
  }
  return over;
}

void Server::startConnection(std::unique_ptr<Transport> transport, ConnectionStrand strand,
                             const std::string& address, const std::optional<std::string>& refusal) {
  const uint64_t session = nextSession_++;
  auto connection =
      std::make_shared<Connection>(std::move(transport), std::move(strand), *context_, session, address);
  // The refusal is queued on the connection's strand before its start, so
  // with several network threads no Hello can be read and answered first.
  if (refusal) {
    connection->refuse(wire::ERROR_CODE_TOO_MANY_CONNECTIONS, *refusal);
  } else {
    connections_[session] = connection;
  }
  connection->start();
}

std::optional<std::string> Server::unhealthy() {
  if (!serving_) return std::string("not serving (starting or stopping)");
  // A read by primary key: proves the store file is still readable.
  auto probe = store_->knowsToken("healthz probe");
  if (!probe.isOk()) return "store: " + probe.status().message();
  return std::nullopt;
}

void Server::awaitHangup() {
  hangup_.async_wait([this](const boost::system::error_code& ec, int) {
    if (ec) return;
    const Status reopened = reopenLogFile();
    if (reopened.isOk()) {
      logEvent(LogLevel::kInfo, "log_reopened", {});
    } else {
      logEvent(LogLevel::kError, "log_reopen_failed", {{"error", reopened.message()}});
    }
    awaitHangup();
  });
}

void Server::pingWatchdog() {
  uint64_t micros = 0;
  if (sd_watchdog_enabled(0, &micros) <= 0 || micros == 0) return;
  // Pinged from the accept strand: a wedged loop stops the pings and
  // systemd restarts the server.
  sd_notify(0, "WATCHDOG=1");
  watchdog_.expires_after(std::chrono::microseconds(micros / 2));
  watchdog_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec && !stopping_) pingWatchdog();
  });
}

void Server::run() {
  if (cluster_) {
    logEvent(LogLevel::kInfo, "listening",
             {{"address", config_.listenAddress},
              {"port", static_cast<uint64_t>(port_)},
              {"cluster", config_.cluster},
              {"node", cluster_->name()},
              {"tls", tls_ != nullptr}});
  } else {
    logEvent(LogLevel::kInfo, "listening",
             {{"address", config_.listenAddress},
              {"port", static_cast<uint64_t>(port_)},
              {"data", config_.dataDirectory},
              {"tls", tls_ != nullptr}});
  }
  signals_.async_wait([this](const boost::system::error_code& ec, int signal) {
    if (ec) return;
    logEvent(LogLevel::kInfo, "signal", {{"signal", static_cast<int64_t>(signal)}});
    shutdown();
  });
  awaitHangup();
  accept();
  serving_ = true;
  // Type=notify units start their dependants only now (a no-op elsewhere).
  sd_notify(0, "READY=1\nSTATUS=serving");
  asio::post(strand_, [this] { pingWatchdog(); });
  std::vector<std::thread> threads;
  for (int i = 1; i < config_.networkThreads; ++i) threads.emplace_back([this] { io_.run(); });
  io_.run();
  for (auto& t : threads) t.join();
  stopBulk();
  workers_.join();
  logEvent(LogLevel::kInfo, "stopped", {});
}

void Server::stop() {
  asio::post(strand_, [this] { shutdown(); });
}

void Server::accept() {
  acceptor_.async_accept(
      asio::make_strand(io_), [this](const boost::system::error_code& ec, tcp::socket socket) {
        if (ec) {
          if (!stopping_) accept();
          return;
        }
        boost::system::error_code ignored;
        socket.set_option(tcp::no_delay(true), ignored);
        if (config_.limits.sendBufferBytes > 0) {
          socket.set_option(asio::socket_base::send_buffer_size(config_.limits.sendBufferBytes), ignored);
        }
        const auto remote = socket.remote_endpoint(ignored);
        const std::string address = remote.address().to_string();
        const auto over = admission(address);
        ConnectionStrand strand = asio::make_strand(socket.get_executor());
        auto transport = makeStreamTransport(std::move(socket), tls_.get(), strand);
        // Refused in the protocol (an Error frame), which a client library reads.
        startConnection(std::move(transport), std::move(strand), address, over);
        accept();
      });
}

// Prunes finished connections and counts the live ones: all of this
// address's, and those not authenticated yet, from it and in total
// (docs/PROTOCOL.md §1.1: a peer must not hold many slots without showing a
// known token).
std::optional<std::string> Server::overLimits(const std::string& address) {
  int sameAddress = 0, unauthenticatedHere = 0, unauthenticated = 0;
  for (auto it = connections_.begin(); it != connections_.end();) {
    auto live = it->second.lock();
    if (!live || !live->live()) {
      it = connections_.erase(it);
      continue;
    }
    const bool here = live->address() == address;
    sameAddress += here ? 1 : 0;
    if (!live->authenticated()) {
      ++unauthenticated;
      unauthenticatedHere += here ? 1 : 0;
    }
    ++it;
  }
  const Limits& l = config_.limits;
  if (sameAddress >= l.connectionsPerAddress) {
    return "more than " + std::to_string(l.connectionsPerAddress) + " connections from " + address;
  }
  if (unauthenticatedHere >= l.unauthenticatedPerAddress) {
    return "more than " + std::to_string(l.unauthenticatedPerAddress) + " unauthenticated connections from " +
           address + " (--unauthenticated-per-address)";
  }
  if (unauthenticated >= l.unauthenticatedTotal) {
    return "more than " + std::to_string(l.unauthenticatedTotal) +
           " unauthenticated connections in all (--unauthenticated-total)";
  }
  return std::nullopt;
}

void Server::shutdown() {
  if (stopping_) return;
  stopping_ = true;
  serving_ = false;
  sd_notify(0, "STOPPING=1");
  boost::system::error_code ignored;
  acceptor_.close(ignored);
  if (web_) web_->stop();
  signals_.cancel(ignored);
  hangup_.cancel(ignored);
  watchdog_.cancel();
  // Durable writes first; their acks pass through the document strands, so
  // the goodbye waits a moment for them, then the clients get their queues
  // flushed before the loop stops.
  store_->close();
  auto goodbye = std::make_shared<asio::steady_timer>(strand_, std::chrono::milliseconds(200));
  goodbye->async_wait([this, goodbye](const boost::system::error_code&) {
    for (auto& [session, weak] : connections_) {
      if (auto c = weak.lock()) c->shutdown();
    }
    auto stop = std::make_shared<asio::steady_timer>(io_, std::chrono::milliseconds(500));
    stop->async_wait([this, stop](const boost::system::error_code&) { io_.stop(); });
  });
}

}  // namespace tessera::server
