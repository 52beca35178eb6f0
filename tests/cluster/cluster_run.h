// A cluster for the integration tests: a real 3-server NATS JetStream
// cluster and real tessera-server nodes on it (--cluster), each on
// 127.0.0.1 with an ephemeral port, and what the tests check against: the
// journal as JetStream holds it, replayed locally into the surface a viewer
// must see.
#pragma once

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "cluster/nats_cluster.h"
#include "integration/server_process.h"
#include "server/store/store.h"

namespace tessera::testing {

inline constexpr int kClusterMaxLevel = 3;
inline constexpr uint32_t kClusterBase = 1, kClusterMax = 3;
inline constexpr double kClusterAngle = 15;
inline constexpr const char* kEditorToken = "editor-token-0123456789";
inline constexpr const char* kViewerToken = "viewer-token-0123456789";

struct ClusterRun {
  std::string directory;
  NatsCluster nats;
  std::vector<std::unique_ptr<ServerProcess>> nodes;  // null once killed

  // `nodes` tessera-servers named node0.. on a fresh 3-server NATS cluster.
  static Expected<std::unique_ptr<ClusterRun>> start(int nodes, int leaseMs = 1500,
                                                     std::vector<std::string> extraArgs = {},
                                                     const std::string& natsMaxPayload = "8MB");
  ~ClusterRun();                // kills what runs; removes the logs unless TESSERA_KEEP_NATS is set
  Status startNode(int index);  // again, after a kill
  std::string nodeName(int index) const { return "node" + std::to_string(index); }
  client::SessionOptions session(int node, const std::string& name, const std::string& token) const;
  // Creates the creased cube (tests/data/cube.obj, cube.tags) through node 0
  // and grants the editor and viewer tokens; its document id.
  Expected<uint64_t> createCube();

 private:
  ClusterRun(std::string dir, NatsCluster n) : directory(std::move(dir)), nats(std::move(n)) {}
  int leaseMs_ = 1500;
  std::vector<std::string> extraArgs_;  // for every node (benchmarks raise limits)
};

// The surface hash (PROTOCOL 6.5) of the document as the journal in
// JetStream holds it, replayed here, at the tests' profile; and the journal.
struct JournalState {
  uint64_t version = 0;  // document version (1 + entries)
  uint64_t surfaceHash = 0;
  std::vector<store::JournalEntry> entries;
};
Expected<JournalState> journalState(const NatsCluster& nats, uint64_t documentId);

// A viewer of the document at the tests' profile on one node: opened and
// subscribed; its view is filled by followUntil. No session (and `error`
// set) when the node refused.
struct ClusterViewer {
  std::unique_ptr<client::Session> session;
  std::unique_ptr<client::DocumentView> view;
  std::string error;
};
ClusterViewer viewerOn(ClusterRun& run, int node, uint64_t documentId);

// An offset move of a level-1 vertex of the cube by at most `reach` per
// axis: inside the document's grid whatever the order of a storm's moves.
wire::ClientMessage smallMove(uint64_t documentId, std::mt19937& rng, double reach = 0.004);

// Reads `session` until `view` holds `version` (or a later one), resubscribing
// after a gap; false on timeout. Error frames (a document moved) are skipped.
bool followUntil(client::Session& session, client::DocumentView& view, uint64_t version, double seconds);

}  // namespace tessera::testing
