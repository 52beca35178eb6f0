// Which command of an open document goes to which call of its endpoint
// (docs/PROTOCOL.md §5): the one routing that the connection and the
// document host's fuzz target share, so what is fuzzed is what is served.
// The caller checks the session's side first (roles, per-session limits).
#pragma once

#include <memory>
#include <string>

#include "protocol/tessera.pb.h"
#include "server/document/document_endpoint.h"
#include "server/document/subscriber.h"

namespace tessera::server {

// An edit of the document (every command that changes it, EditBatch and
// AddMorphKey included): it needs the editor role.
bool isEditCommand(const wire::ClientMessage& message);

// Hands `message` to the document; false for a command that is not a
// document's (the caller answers it). An Unsubscribe's Ack is the caller's.
bool dispatchToDocument(DocumentEndpoint& document, const std::shared_ptr<Subscriber>& who,
                        const std::string& authorName, wire::ClientMessage message);

}  // namespace tessera::server
