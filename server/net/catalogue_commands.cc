#include "server/net/catalogue_commands.h"

#include <algorithm>
#include <string>

#include "protocol/handshake.h"
#include "server/base/log.h"
#include "server/document/journal_entry.h"
#include "server/document/replies.h"

namespace tessera::server {

wire::ServerMessage listDocuments(store::Store& store, const CatalogueCaller& caller, uint64_t clientSeq) {
  auto documents = store.listDocuments();
  if (!documents.isOk()) return rejectFor(clientSeq, documents.status());
  wire::ServerMessage m;
  m.mutable_document_list()->set_client_seq(clientSeq);
  for (const store::DocumentSummary& d : *documents) {
    if (!caller.roleOn(d.id)) continue;  // only what this token may read
    wire::DocumentInfo* info = m.mutable_document_list()->add_documents();
    info->set_document_id(d.id.value);
    info->set_name(d.name);
    info->set_version(documentVersionAfter(d.latestVersion));
  }
  return m;
}

wire::ServerMessage deleteDocument(store::Store& store, DocumentOpener& opener, const CatalogueCaller& caller,
                                   uint64_t clientSeq, store::DocumentId id) {
  const auto role = caller.roleOn(id);
  if (!role || *role < store::Role::kAdmin) {
    return rejectWith(clientSeq, wire::REJECT_REASON_PERMISSION_DENIED,
                      "deleting document " + std::to_string(id.value) + " needs the admin role");
  }
  Status deleted = store.deleteDocument(id);
  if (!deleted.isOk()) {
    return rejectFor(clientSeq, deleted);
  }
  opener.forget(id);
  logEvent(LogLevel::kInfo, "document_deleted", {{"doc", id.value}, {"session", caller.session}});
  return ackFor(clientSeq, id.value);
}

wire::ServerMessage grantToken(store::Store& store, const CatalogueCaller& caller, uint64_t clientSeq,
                               const wire::GrantToken& request) {
  if (!caller.globalRole || *caller.globalRole < store::Role::kAdmin) {
    return rejectWith(clientSeq, wire::REJECT_REASON_PERMISSION_DENIED,
                      "granting tokens needs an admin token");
  }
  if (request.token().empty() || request.token().size() > kMaxTokenBytes) {
    return rejectWith(clientSeq, wire::REJECT_REASON_INVALID_ARGUMENT,
                      "grant: the token must have 1.." + std::to_string(kMaxTokenBytes) + " bytes");
  }
  store::Role role;
  switch (request.role()) {
    case wire::ROLE_VIEWER:
      role = store::Role::kViewer;
      break;
    case wire::ROLE_EDITOR:
      role = store::Role::kEditor;
      break;
    case wire::ROLE_ADMIN:
      role = store::Role::kAdmin;
      break;
    default:
      return rejectWith(clientSeq, wire::REJECT_REASON_INVALID_ARGUMENT, "grant: no role given");
  }
  const store::TokenScope scope = request.document_id() == 0
                                      ? store::TokenScope::allDocuments()
                                      : store::TokenScope::document(store::DocumentId{request.document_id()});
  Status granted = store.addToken(scope, request.token(), role);
  if (!granted.isOk()) {
    return rejectFor(clientSeq, granted);
  }
  logEvent(LogLevel::kInfo, "token_granted",
           {{"session", caller.session}, {"scope", scope.toString()}, {"role", store::roleName(role)}});
  return ackFor(clientSeq, request.document_id());
}

wire::ServerMessage serverStats(const ServerStats& stats, store::Store& store, const ServerConfig& config,
                                uint64_t clientSeq, uint64_t ownQueueBytes) {
  const ServerStats& s = stats;
  const double uptime = std::max(1e-9, s.uptimeSeconds());
  const double edits = static_cast<double>(s.edits.load());
  const double regions = std::max<double>(1, static_cast<double>(s.regionsEncoded.load()));
  const store::StoreStats storeStats = store.stats();
  wire::ServerMessage m;
  m.mutable_stats_reply()->set_client_seq(clientSeq);
  auto add = [&](const char* name, double value) {
    wire::Stat* stat = m.mutable_stats_reply()->add_stats();
    stat->set_name(name);
    stat->set_value(value);
  };
  add("connections", static_cast<double>(s.connections.load()));
  add("connections_total", static_cast<double>(s.connectionsTotal.load()));
  add("uptime_seconds", uptime);
  add("edits", edits);
  add("edits_per_second", edits / uptime);
  add("rejects", static_cast<double>(s.rejects.load()));
  add("bytes_sent", static_cast<double>(s.bytesSent.load()));
  add("bytes_per_second", static_cast<double>(s.bytesSent.load()) / uptime);
  add("frames_sent", static_cast<double>(s.framesSent.load()));
  add("queue_bytes_max", static_cast<double>(s.queueBytesMax.load()));
  add("queue_bytes_self", static_cast<double>(ownQueueBytes));
  add("delta_merges", static_cast<double>(s.deltaMerges.load()));
  add("resyncs", static_cast<double>(s.resyncs.load()));
  add("tessellate_ms_per_edit", edits > 0 ? s.tessellateMicros.load() / 1000.0 / edits : 0.0);
  add("encode_ms_per_region", s.encodeMicros.load() / 1000.0 / regions);
  add("regions_encoded", static_cast<double>(s.regionsEncoded.load()));
  add("deltas", static_cast<double>(s.deltaFlushes.load()));
  add("delta_regions", static_cast<double>(s.deltaRegions.load()));
  add("delta_regions_layout_ids", static_cast<double>(s.deltaRegionsLayoutIds.load()));
  add("edits_per_delta",
      s.deltaFlushes.load() > 0 ? edits / static_cast<double>(s.deltaFlushes.load()) : 0.0);
  add("edit_to_durable_ms", edits > 0 ? s.commitMicros.load() / 1000.0 / edits : 0.0);
  add("store_batches", static_cast<double>(storeStats.batches));
  add("store_average_batch", storeStats.averageBatchSize);
  add("store_last_commit_ms", static_cast<double>(storeStats.lastCommitLatency.count()) / 1000.0);
  // 1: each acknowledged write is on disk first; 0: it is not (a majority's
  // memory and page cache); -1: per the NATS servers' configuration.
  const store::WriteSync sync = store.durability().sync;
  add("acknowledgement_syncs_each_write", sync == store::WriteSync::kEachWrite      ? 1.0
                                          : sync == store::WriteSync::kNotEachWrite ? 0.0
                                                                                    : -1.0);
  add("tiles_built", static_cast<double>(s.tilesBuilt.load()));
  add("tiles_encoded", static_cast<double>(s.tilesEncoded.load()));
  add("tile_cache_hits", static_cast<double>(s.tileCacheHits.load()));
  add("tile_cache_evictions", static_cast<double>(s.tileCacheEvictions.load()));
  add("tile_cache_bytes", static_cast<double>(s.tileCacheBytes.load()));
  add("views_received", static_cast<double>(s.viewsReceived.load()));
  add("views_applied", static_cast<double>(s.viewsApplied.load()));
  add("views_unchanged_by_edits", static_cast<double>(s.viewsUnchangedByEdits.load()));
  add("view_continuations", static_cast<double>(s.viewContinuations.load()));
  add("view_subscribers", static_cast<double>(s.viewSubscribers.load()));
  if (!config.cluster.empty()) {
    add("cluster_node", static_cast<double>(s.clusterNode.load()));
    add("documents_owned", static_cast<double>(s.documentsOwned.load()));
    add("documents_moved", static_cast<double>(s.documentsMoved.load()));
    add("cluster_messages_dropped", static_cast<double>(s.clusterMessagesDropped.load()));
    add("remote_sessions", static_cast<double>(s.remoteSessions.load()));
  }
  return m;
}

}  // namespace tessera::server
