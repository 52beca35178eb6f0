// tessera-server's settings: where it listens and stores, and every limit
// (docs/PROTOCOL.md §9), each settable on the command line.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/util/status.h"

namespace tessera::server {

struct Limits {
  uint32_t maxFrameBytes = 64u << 20;     // a frame's payload (CreateDocument carries a mesh)
  uint64_t maxBaseMeshBytes = 48u << 20;  // CreateDocument.mesh, AddMorphKey.mesh
  int maxLevel = 6;                       // of any document
  int64_t maxTrianglesPerSubscriber = 4'000'000;
  double commandsPerSecond = 200;  // per connection (token bucket, burst = 1 s)
  int connectionsPerAddress = 2000;
  // Before a Hello with a known token (docs/PROTOCOL.md §9): the Hello's frame, and
  // the connections that have not authenticated (anonymous ones included).
  uint32_t helloMaxBytes = 16u << 10;
  int unauthenticatedPerAddress = 64;
  int unauthenticatedTotal = 512;
  // Failed authentications space an address's attempts: the delay doubles
  // per recent failure from the first, up to the second (auth_throttle.h).
  double authFailureDelayMs = 250;
  double authFailureMaxDelayMs = 30'000;
  // After authentication: distinct LOD profiles a document keeps at once
  // (each is a tessellation updated on every edit), documents a session
  // subscribes at once, ids in one selection.
  int profilesPerDocument = 8;
  int subscriptionsPerSession = 16;
  int selectionMaxIds = 1024;
  uint64_t queueSoftBytes = 8u << 20;   // per client: coalesce queued deltas above this
  uint64_t queueHardBytes = 32u << 20;  // per client: drop them and resync with a snapshot
  uint32_t queueMaxMessages = 4096;
  int sendBufferBytes = 0;  // SO_SNDBUF per connection; 0 keeps the system's
};

struct Timeouts {
  double handshakeSeconds = 10;
  double idleSeconds = 300;  // no frame at all from the client
  double writeSeconds = 30;  // one write making no progress
};

// std::thread::hardware_concurrency(), at least 1.
int defaultNetworkThreads();

struct ServerConfig {
  std::string listenAddress = "127.0.0.1";
  uint16_t port = 7878;  // 0: any free port
  std::string dataDirectory = "tessera-data";
  // Cluster mode (docs/CLUSTER.md): the NATS servers, comma
  // separated; empty runs on the SQLite store of dataDirectory.
  std::string cluster;
  std::string nodeName;     // this node in logs, stats and leases (default: the host name)
  int clusterReplicas = 3;  // JetStream replicas of the journal, blobs and buckets
  // Refuse to start on a store that cannot put each acknowledged write on
  // disk before its acknowledgement (docs/CLUSTER.md "What an acknowledged
  // edit survives").
  bool requireFsync = false;
  // A document's owner renews its lease every third of this; a dead owner's
  // documents are taken over once it runs out (docs/CLUSTER.md, "Failover").
  int64_t leaseMs = 3000;
  std::string portFile;                       // write the bound port here (tests, scripts)
  std::string adminTokenFile;                 // a token read at start-up and granted admin on everything
  std::string tlsCertificate, tlsPrivateKey;  // both set: TLS on the listening port
  // Connections' reads, writes and the fan-out of deltas: one per core, so
  // a thousand subscribers' writes do not hold up editors' reads and acks.
  int networkThreads = defaultNetworkThreads();
  int workerThreads = 1;
  // Bulk work (docs/ARCHITECTURE.md, "Bulk work"): importing and loading documents, and the
  // commands of a document whose estimated work is above bulkTriangles
  // (a profile's first tessellation, an export), run on these threads, at
  // a lower CPU priority, so edits and deltas of small documents never wait
  // behind them.
  int bulkThreads = 1;
  int64_t bulkTriangles = 200'000;
  uint64_t snapshotEvery = 200;  // journal entries between document snapshots
  // Deltas of one document at most every max(deltaIntervalMs, subscribers /
  // deltaFramesPerSecond): under load a delta covers the edits of the
  // interval. The frame budget keeps the fan-out (deltas x subscribers) of a
  // document bounded, so a thousand viewers get fewer, fuller deltas while
  // ten get every burst at once. 0 turns either bound off.
  double deltaIntervalMs = 0;
  double deltaFramesPerSecond = 40000;
  // A delta goes out as soon as its flush has encoded it; only acks (and
  // recorders' commands) promise durability. With this set, a delta also
  // waits until its last command is durable, so no viewer ever sees a
  // state a crash could take back, at the cost of the fsync in every
  // viewer's latency.
  bool deltasAfterDurable = false;
  // View-dependent subscriptions (docs/VIEWS.md "The server"): a
  // document's encoded tiles are kept up to this many bytes (least recently
  // used go first), and each subscriber's camera is applied at most once
  // per viewIntervalMs (a newer view replaces one waiting).
  uint64_t tileCacheBytes = 256u << 20;
  double viewIntervalMs = 50;
  Limits limits;
  Timeouts timeouts;
  bool verbose = false;
  // Operations (docs/OPERATIONS.md, "Logs"): JSON log lines go to this file (reopened on
  // SIGHUP, for logrotate) instead of stderr; the HTTP endpoint for
  // /healthz and /metrics is off unless a port is given (0 picks one).
  std::string logFile;
  std::string httpListenAddress = "127.0.0.1";
  int httpPort = -1;
  std::string httpPortFile;
  // The browser viewer (docs/WEB_VIEWER.md): the protocol over
  // WebSocket on /ws and the viewer's files, on this port of listenAddress
  // (off unless given; 0 picks one). TLS, when on, covers it too.
  int wsPort = -1;
  std::string wsPortFile;
  std::string webRoot;                        // the built client/web files; empty: the build's own
  std::vector<std::string> wsAllowedOrigins;  // besides the page's own; "*" any
};

// The checks that span several options, after each option's own.
Status checkServerConfig(const ServerConfig& config);

}  // namespace tessera::server
