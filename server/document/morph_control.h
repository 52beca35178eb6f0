// The coarse morph stream (docs/PROTOCOL.md §14, "The coarse stream"): a
// morph document's base control points at a time t, and on request the
// topology and options a client needs to subdivide them itself (the
// triangles, creases, vertex sharpness, rules, deepest level and the 2D
// morph's images).
#pragma once

#include <cstdint>

#include "core/morph/keyed_document.h"
#include "core/util/status.h"
#include "protocol/tessera.pb.h"

namespace tessera::server {

// The MorphControl answering `request` (client_seq `clientSeq`) for document
// `documentId` at `version`; an error when `doc` has no time `request.t()`
// (the error names the document) or its morph cannot be built there.
Expected<wire::ServerMessage> morphControlMessage(const KeyedDocument& doc, uint64_t documentId,
                                                  uint64_t version, uint64_t clientSeq,
                                                  const wire::GetMorphControl& request);

}  // namespace tessera::server
