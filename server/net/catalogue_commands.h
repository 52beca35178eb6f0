// The commands a session sends outside any open document: list, delete,
// grant a token, server stats (docs/PROTOCOL.md §5 and §7). Each checks the
// caller's role and returns what to answer: an Ack, a list or stats, or a
// Reject that names what was refused and why. None of them touches the
// session's own state; the connection does that from the answer.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "protocol/tessera.pb.h"
#include "server/base/config.h"
#include "server/base/server_stats.h"
#include "server/document/document_endpoint.h"
#include "server/store/store.h"

namespace tessera::server {

// Who asks: its session, the role its token has on every document (if any)
// and the role it has on one document (its global role or that document's).
struct CatalogueCaller {
  uint64_t session = 0;
  std::optional<store::Role> globalRole;
  std::function<std::optional<store::Role>(store::DocumentId)> roleOn;
};

// Only the documents the caller may read.
wire::ServerMessage listDocuments(store::Store& store, const CatalogueCaller& caller, uint64_t clientSeq);
// Needs the admin role on the document; forgets its open host on success.
wire::ServerMessage deleteDocument(store::Store& store, DocumentOpener& opener, const CatalogueCaller& caller,
                                   uint64_t clientSeq, store::DocumentId id);
// Needs an admin token for every document.
wire::ServerMessage grantToken(store::Store& store, const CatalogueCaller& caller, uint64_t clientSeq,
                               const wire::GrantToken& request);
// The server's counters; `ownQueueBytes`: the caller's own queue.
wire::ServerMessage serverStats(const ServerStats& stats, store::Store& store, const ServerConfig& config,
                                uint64_t clientSeq, uint64_t ownQueueBytes);

}  // namespace tessera::server
