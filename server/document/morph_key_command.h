// AddMorphKey (docs/PROTOCOL.md §14): the second key's mesh imported,
// checked against key 0's connectivity, and added with its two images.
#pragma once

#include "core/morph/keyed_document.h"
#include "core/util/status.h"
#include "protocol/tessera.pb.h"
#include "server/document/journal_entry.h"
#include "server/store/store.h"

namespace tessera::server {

Status applyAddMorphKey(KeyedDocument& doc, store::DocumentId id, const wire::AddMorphKey& request,
                        JournalEntry& entry);

}  // namespace tessera::server
