#include "server/app/command_line.h"

#include <CLI/CLI.hpp>
#include <limits>

#include "tessera/version.h"

namespace tessera::server {

namespace {

template <typename T>
CLI::Range atLeast(T minimum) {
  return CLI::Range(minimum, std::numeric_limits<T>::max());
}

void addNetworkOptions(CLI::App& app, ServerConfig& c) {
  const char* g = "Network";
  app.add_option("--data", c.dataDirectory, "data directory (the SQLite store)")
      ->capture_default_str()
      ->group(g);
  app.add_option("--listen", c.listenAddress, "address to bind")->capture_default_str()->group(g);
  app.add_option("--port", c.port, "port; 0 picks a free one")->capture_default_str()->group(g);
  app.add_option("--port-file", c.portFile, "write the bound port to this file once listening")->group(g);
  app.add_option("--admin-token-file", c.adminTokenFile,
                 "grant the token in this file admin rights on every document")
      ->group(g);
  app.add_option("--tls-cert", c.tlsCertificate, "serve TLS with this PEM certificate chain (with --tls-key)")
      ->group(g);
  app.add_option("--tls-key", c.tlsPrivateKey, "the PEM private key of --tls-cert")->group(g);
  app.add_option("--network-threads", c.networkThreads, "reads, writes and fan-out (default: one per core)")
      ->check(atLeast(1))
      ->group(g);
  app.add_option("--worker-threads", c.workerThreads, "tessellation and encoding")
      ->check(atLeast(1))
      ->capture_default_str()
      ->group(g);
  app.add_option("--bulk-threads", c.bulkThreads, "imports, loads and large documents' heavy commands")
      ->check(atLeast(1))
      ->capture_default_str()
      ->group(g);
  app.add_option("--bulk-triangles", c.bulkTriangles, "work estimated above this many triangles is bulk")
      ->check(atLeast<int64_t>(0))
      ->capture_default_str()
      ->group(g);
}

void addClusterOptions(CLI::App& app, ServerConfig& c) {
  const char* g = "Cluster (docs/CLUSTER.md)";
  app.add_option("--cluster", c.cluster,
                 "run as a node of a cluster on these NATS JetStream servers (nats://host:port,...) "
                 "instead of on --data's SQLite store")
      ->group(g);
  app.add_option("--node-name", c.nodeName, "this node's name in the cluster (default: the host name)")
      ->group(g);
  app.add_flag("--require-fsync", c.requireFsync,
               "refuse to start unless each acknowledged edit is on disk before its acknowledgement "
               "(nats-server before 2.10 cannot; docs/CLUSTER.md)");
  app.add_option("--cluster-replicas", c.clusterReplicas,
                 "JetStream replicas of the journal, snapshots and catalogue (3 in a 3-server NATS cluster)")
      ->check(CLI::Range(1, 5))
      ->capture_default_str()
      ->group(g);
  app.add_option("--lease-ms", c.leaseMs,
                 "a document owner's lease: a dead owner's documents move to another node after this")
      ->check(CLI::Range(int64_t{300}, int64_t{600'000}))
      ->capture_default_str()
      ->group(g);
}

void addLimitOptions(CLI::App& app, ServerConfig& c) {
  const char* g = "Limits";
  Limits& l = c.limits;
  app.add_option("--max-frame-bytes", l.maxFrameBytes, "a frame's payload")
      ->check(atLeast<uint32_t>(1024))
      ->capture_default_str()
      ->group(g);
  app.add_option("--max-mesh-bytes", l.maxBaseMeshBytes, "a created document's base mesh file")
      ->check(atLeast<uint64_t>(1))
      ->capture_default_str()
      ->group(g);
  app.add_option("--max-level", l.maxLevel, "subdivision level of any document")
      ->check(CLI::Range(0, 12))
      ->capture_default_str()
      ->group(g);
  app.add_option("--max-triangles", l.maxTrianglesPerSubscriber, "per subscribed profile and per export")
      ->check(atLeast<int64_t>(1))
      ->capture_default_str()
      ->group(g);
  app.add_option("--commands-per-second", l.commandsPerSecond, "per connection (token bucket, burst 1 s)")
      ->check(CLI::Range(0.001, 1e9))
      ->capture_default_str()
      ->group(g);
  app.add_option("--connections-per-address", l.connectionsPerAddress, "connections from one address")
      ->check(atLeast(1))
      ->capture_default_str()
      ->group(g);
  app.add_option("--hello-max-bytes", l.helloMaxBytes, "the first frame (the Hello)")
      ->check(atLeast<uint32_t>(256))
      ->capture_default_str()
      ->group(g);
  app.add_option("--unauthenticated-per-address", l.unauthenticatedPerAddress,
                 "connections without a known token yet, per address")
      ->check(atLeast(1))
      ->capture_default_str()
      ->group(g);
  app.add_option("--unauthenticated-total", l.unauthenticatedTotal, "and over all addresses")
      ->check(atLeast(1))
      ->capture_default_str()
      ->group(g);
  app.add_option("--auth-failure-delay-ms", l.authFailureDelayMs,
                 "after a failed token an address's attempts are spaced by this, doubling per recent failure")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str()
      ->group(g);
  app.add_option("--auth-failure-max-delay-ms", l.authFailureMaxDelayMs, "up to this")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str()
      ->group(g);
  app.add_option("--profiles-per-document", l.profilesPerDocument, "distinct LOD profiles held per document")
      ->check(atLeast(1))
      ->capture_default_str()
      ->group(g);
  app.add_option("--subscriptions-per-session", l.subscriptionsPerSession,
                 "documents one session subscribes at once")
      ->check(atLeast(1))
      ->capture_default_str()
      ->group(g);
  app.add_option("--selection-max-ids", l.selectionMaxIds, "ids in one selection")
      ->check(atLeast(0))
      ->capture_default_str()
      ->group(g);
  app.add_option("--queue-soft-bytes", l.queueSoftBytes, "per client: coalesce queued deltas above this")
      ->check(atLeast<uint64_t>(1024))
      ->capture_default_str()
      ->group(g);
  app.add_option("--queue-hard-bytes", l.queueHardBytes, "per client: drop them and resync with a snapshot")
      ->check(atLeast<uint64_t>(1024))
      ->capture_default_str()
      ->group(g);
  app.add_option("--queue-messages", l.queueMaxMessages, "per client: queued messages")
      ->check(atLeast<uint32_t>(4))
      ->capture_default_str()
      ->group(g);
  app.add_option("--send-buffer-bytes", l.sendBufferBytes,
                 "kernel send buffer per connection (0: the system's)")
      ->check(atLeast(0))
      ->capture_default_str()
      ->group(g);
}

void addTimingOptions(CLI::App& app, ServerConfig& c) {
  const char* g = "Timing";
  app.add_option("--idle-timeout", c.timeouts.idleSeconds, "seconds without a frame from a client")
      ->check(CLI::Range(0.01, 1e9))
      ->capture_default_str()
      ->group(g);
  app.add_option("--write-timeout", c.timeouts.writeSeconds, "seconds one write may make no progress")
      ->check(CLI::Range(0.01, 1e9))
      ->capture_default_str()
      ->group(g);
  app.add_option("--handshake-timeout", c.timeouts.handshakeSeconds,
                 "seconds from connecting to a known token")
      ->check(CLI::Range(0.01, 1e9))
      ->capture_default_str()
      ->group(g);
  app.add_option("--snapshot-every", c.snapshotEvery, "journal entries between document snapshots")
      ->check(atLeast<uint64_t>(1))
      ->capture_default_str()
      ->group(g);
  app.add_option("--delta-interval-ms", c.deltaIntervalMs,
                 "at most one delta per document every this many ms (edits between share it)")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str()
      ->group(g);
  app.add_option("--tile-cache-bytes", c.tileCacheBytes,
                 "encoded tiles kept per document for view-dependent subscribers (least recently used go)")
      ->check(atLeast<uint64_t>(1))
      ->capture_default_str()
      ->group(g);
  app.add_option(
         "--view-interval-ms", c.viewIntervalMs,
         "a subscriber's camera is applied at most once per this many ms (newer views replace waiting ones)")
      ->check(CLI::Range(0.0, 1e6))
      ->capture_default_str()
      ->group(g);
  app.add_option("--delta-frames-per-second", c.deltaFramesPerSecond,
                 "and at most this many delta frames per second per document over all subscribers")
      ->check(CLI::Range(0.0, 1e12))
      ->capture_default_str()
      ->group(g);
  app.add_flag("--deltas-after-durable", c.deltasAfterDurable,
               "deltas also wait for their last command's journal commit (acks always wait)")
      ->group(g);
}

void addOperationsOptions(CLI::App& app, ServerConfig& c) {
  const char* g = "Operations";
  app.add_option("--log-file", c.logFile, "JSON log lines to this file instead of stderr; reopened on SIGHUP")
      ->group(g);
  app.add_option("--http-port", c.httpPort,
                 "serve /healthz and /metrics over HTTP on this port (off by default; 0 picks one)")
      ->check(CLI::Range(0, 65535))
      ->group(g);
  app.add_option("--http-listen", c.httpListenAddress, "address of the HTTP endpoint")
      ->capture_default_str()
      ->group(g);
  app.add_option("--http-port-file", c.httpPortFile, "write the HTTP endpoint's bound port to this file")
      ->group(g);
  const char* w = "Browser viewer (docs/WEB_VIEWER.md)";
  app.add_option("--ws-port", c.wsPort,
                 "serve the web viewer and the protocol over WebSocket (/ws) on this port of --listen "
                 "(off by default; 0 picks one; TLS when --tls-cert is set)")
      ->check(CLI::Range(0, 65535))
      ->group(w);
  app.add_option("--ws-port-file", c.wsPortFile, "write the web port's bound port to this file")->group(w);
  app.add_option("--web-root", c.webRoot, "the built web viewer's files (default: this build's)")->group(w);
  app.add_option("--ws-allowed-origin", c.wsAllowedOrigins,
                 "a page origin (https://host:port) that may open WebSockets besides the viewer's own; "
                 "repeatable; * for any")
      ->group(w);
  app.add_flag("--verbose", c.verbose, "debug logs")->group(g);
}

}  // namespace

ParsedCommandLine parseServerCommandLine(const std::vector<std::string>& args) {
  ParsedCommandLine parsed;
  ServerCommandLine& command = parsed.command;
  CLI::App app{"tessera-server: hierarchical subdivision documents served to editors and viewers",
               "tessera-server"};
  app.set_version_flag("--version", std::string("tessera-server ") + kVersion);
  app.set_config("--config", "",
                 "read options from this file: one 'name = value' per line, names as the long options");
  app.allow_config_extras(CLI::config_extras_mode::error);
  app.fallthrough();  // serving options may follow a subcommand: health --config F
  // As with most servers' flags, a repeated option takes its last value, so
  // a wrapper can append an override to a fixed command line.
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  addNetworkOptions(app, command.config);
  addClusterOptions(app, command.config);
  addLimitOptions(app, command.config);
  addTimingOptions(app, command.config);
  addOperationsOptions(app, command.config);

  CLI::App* token = app.add_subcommand("token", "manage access tokens")->require_subcommand(1);
  CLI::App* tokenNew =
      token->add_subcommand("new", "print a new random token and store its hash in --data's store");
  tokenNew->add_option("--role", command.role, "viewer, editor or admin")
      ->check(CLI::IsMember({"viewer", "editor", "admin"}))
      ->capture_default_str();
  tokenNew->add_option("--document", command.documentId, "one document's id (default: every document)")
      ->check(atLeast<uint64_t>(1));
  CLI::App* backup = app.add_subcommand("backup", "copy the store of --data, online, into a new file");
  backup->add_option("--to", command.path, "the backup file to create (never overwritten)")->required();
  CLI::App* restore =
      app.add_subcommand("restore", "replace the store of --data (server stopped) by a backup");
  restore->add_option("--from", command.path, "the backup file")->required()->check(CLI::ExistingFile);
  CLI::App* health = app.add_subcommand("health", "ask a running server's /healthz; exit 0 when healthy");
  health->add_option("--url", command.url, "default: http://<--http-listen>:<--http-port>/healthz");
  app.require_subcommand(0, 1);

  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last-first
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    parsed.stop = true;
    parsed.output = app.help();
    return parsed;
  } catch (const CLI::CallForAllHelp&) {
    parsed.stop = true;
    parsed.output = app.help("", CLI::AppFormatMode::All);
    return parsed;
  } catch (const CLI::CallForVersion&) {
    parsed.stop = true;
    parsed.output = app.version() + "\n";
    return parsed;
  } catch (const CLI::ConfigError& e) {
    parsed.stop = true;
    parsed.exitCode = 2;
    const CLI::Option* config = app.get_config_ptr();
    parsed.error = "--config " + (config != nullptr ? config->as<std::string>() : std::string()) + ": " +
                   e.what() +
                   " (every name must be a long option of tessera-server --help, without its dashes)";
    return parsed;
  } catch (const CLI::ParseError& e) {
    parsed.stop = true;
    parsed.exitCode = 2;
    parsed.error = e.what();
    return parsed;
  }
  if (tokenNew->parsed()) command.action = ServerAction::kTokenNew;
  if (backup->parsed()) command.action = ServerAction::kBackup;
  if (restore->parsed()) command.action = ServerAction::kRestore;
  if (health->parsed()) command.action = ServerAction::kHealth;
  if (command.action == ServerAction::kServe) {
    if (Status s = checkServerConfig(command.config); !s.isOk()) {
      parsed.stop = true;
      parsed.exitCode = 2;
      parsed.error = s.message();
    }
  }
  return parsed;
}

}  // namespace tessera::server
