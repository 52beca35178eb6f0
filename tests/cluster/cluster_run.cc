#include "cluster/cluster_run.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include "core/hierarchy/ids.h"
#include "core/morph/keyed_document_file.h"
#include "core/tessellation/document_grid.h"
#include "core/tessellation/surface_hash.h"
#include "core/tessellation/tessellation.h"
#include "integration/messages.h"
#include "server/cluster/nats_store.h"
#include "server/document/journal_entry.h"
#include "support/test_meshes.h"

namespace tessera::testing {

Expected<std::unique_ptr<ClusterRun>> ClusterRun::start(int nodes, int leaseMs,
                                                        std::vector<std::string> extraArgs,
                                                        const std::string& natsMaxPayload) {
  TESSERA_ASSIGN_OR_RETURN(NatsCluster nats, NatsCluster::start(3, natsMaxPayload));
  std::unique_ptr<ClusterRun> run(new ClusterRun(makeTempDir("tessera-cluster"), std::move(nats)));
  run->leaseMs_ = leaseMs;
  run->extraArgs_ = std::move(extraArgs);
  run->nodes.resize(static_cast<size_t>(nodes));
  for (int i = 0; i < nodes; ++i) TESSERA_RETURN_IF_ERROR(run->startNode(i));
  return run;
}

ClusterRun::~ClusterRun() {
  nodes.clear();  // SIGKILL: the test is over
  if (std::getenv("TESSERA_KEEP_NATS") == nullptr) {
    std::error_code ignored;
    std::filesystem::remove_all(directory, ignored);
  }
}

Status ClusterRun::startNode(int index) {
  std::vector<std::string> args = {"--cluster",          nats.urls(), "--node-name", nodeName(index),
                                   "--cluster-replicas", "3",         "--lease-ms",  std::to_string(leaseMs_),
                                   "--snapshot-every",   "1000000"};
  args.insert(args.end(), extraArgs_.begin(), extraArgs_.end());
  TESSERA_ASSIGN_OR_RETURN(ServerProcess process,
                           ServerProcess::start(directory + "/" + nodeName(index), args));
  nodes[static_cast<size_t>(index)] = std::make_unique<ServerProcess>(std::move(process));
  return Status::ok();
}

client::SessionOptions ClusterRun::session(int node, const std::string& name,
                                           const std::string& token) const {
  return nodes[static_cast<size_t>(node)]->session(name, token);
}

Expected<uint64_t> ClusterRun::createCube() {
  TESSERA_ASSIGN_OR_RETURN(auto admin, client::Session::connect(session(0, "admin", nodes[0]->adminToken())));
  TESSERA_ASSIGN_OR_RETURN(
      wire::ServerMessage created,
      admin->call(createDocument("cube", fileBytes(sourceTestDataPath("cube.obj")),
                                 fileBytes(sourceTestDataPath("cube.tags")), kClusterMaxLevel),
                  30));
  if (!created.has_ack()) return internalError("create: " + created.DebugString());
  const uint64_t doc = created.ack().document_id();
  for (auto [token, role] : {std::pair{kEditorToken, wire::ROLE_EDITOR}, {kViewerToken, wire::ROLE_VIEWER}}) {
    TESSERA_ASSIGN_OR_RETURN(wire::ServerMessage granted, admin->call(grant(doc, role, token), 30));
    if (!granted.has_ack()) return internalError("grant: " + granted.DebugString());
  }
  return doc;
}

Expected<JournalState> journalState(const NatsCluster& nats, uint64_t documentId) {
  cluster::NatsStoreOptions options;
  TESSERA_ASSIGN_OR_RETURN(options.link.urls, cluster::parseNatsUrls(nats.urls()));
  options.replicas = 3;
  // A server just restarted may still be catching up: retried for a while.
  Expected<store::StoredDocument> loaded = ioError("not tried");
  for (int attempt = 0; attempt < 20 && !loaded.isOk(); ++attempt) {
    auto store = cluster::NatsStore::open(options);
    loaded = store.isOk() ? (*store)->loadDocument(store::DocumentId{documentId})
                          : Expected<store::StoredDocument>(store.status());
    if (!loaded.isOk()) std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  TESSERA_ASSIGN_OR_RETURN(store::StoredDocument stored, std::move(loaded));
  // From the base, never from a snapshot: the snapshots are the server's
  // own output, the journal is what it acknowledged.
  TESSERA_ASSIGN_OR_RETURN(KeyedDocument doc,
                           deserializeKeyedDocument(stored.baseBytes, "the test's replay"));
  JournalState state;
  state.entries = stored.entries;
  if (stored.snapshot) {
    return internalError("journalState: the document has a snapshot at version " +
                         std::to_string(stored.snapshot->version) + "; replay needs the whole journal");
  }
  for (const store::JournalEntry& e : stored.entries) {
    TESSERA_ASSIGN_OR_RETURN(server::JournalEntry decoded, server::decodeJournalEntry(e.bytes, "entry"));
    TESSERA_RETURN_IF_ERROR(server::applyJournalEntry(doc, decoded));
  }
  state.version = 1 + stored.entries.size();
  TESSERA_ASSIGN_OR_RETURN(QuantizationGrid grid, documentGrid(doc.key0()));
  LodProfile profile;
  profile.baseLevel = kClusterBase;
  profile.maxLevel = kClusterMax;
  profile.angleThresholdDegrees = kClusterAngle;
  Document key0 = doc.key0();  // build() takes a document it may evaluate lazily
  TESSERA_ASSIGN_OR_RETURN(Tessellation tessellation, Tessellation::build(key0, profile));
  for (const auto& [id, region] : tessellation.regions())
    state.surfaceHash += regionSurfaceHashOnGrid(region, grid, true);
  return state;
}

ClusterViewer viewerOn(ClusterRun& run, int node, uint64_t documentId) {
  ClusterViewer v;
  auto s = client::Session::connect(run.session(node, "viewer@" + run.nodeName(node), kViewerToken));
  if (!s.isOk()) {
    v.error = "connect: " + s.status().message();
    return v;
  }
  for (const wire::ClientMessage& m :
       {openDocument(documentId), subscribe(documentId, kClusterBase, kClusterMax, kClusterAngle)}) {
    auto reply = (*s)->call(m, 30);
    if (!reply.isOk() || !reply->has_ack()) {
      v.error = reply.isOk() ? reply->DebugString() : reply.status().message();
      return v;
    }
  }
  v.session = std::move(*s);
  v.view = std::make_unique<client::DocumentView>(documentId);
  return v;
}

wire::ClientMessage smallMove(uint64_t documentId, std::mt19937& rng, double reach) {
  std::uniform_int_distribution<uint32_t> vertex(0, 25);  // the cube has 26 level-1 vertices
  std::uniform_real_distribution<double> offset(-reach, reach);
  return moveVertex(documentId, VertexId(1, vertex(rng)).packed(), offset(rng), offset(rng), offset(rng),
                    wire::MOVE_MODE_OFFSET);
}

bool followUntil(client::Session& session, client::DocumentView& view, uint64_t version, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    if (view.ready() && view.version() >= version) return true;
    auto m = session.receive(0.5);
    if (!m.isOk()) {
      if (client::isReceiveTimeout(m.status())) continue;
      return false;
    }
    if (!view.apply(*m).isOk() || view.needsResync()) {
      // A gap: ask for a snapshot again (as a viewer does).
      (void)session.send(subscribe(view.documentId(), kClusterBase, kClusterMax, kClusterAngle));
    }
  }
  return view.ready() && view.version() >= version;
}

}  // namespace tessera::testing
