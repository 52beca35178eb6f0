// The intake stage of a document (docs/ARCHITECTURE.md, "One edit, end to
// end"): a client's command turned into a change of the document
// (docs/PROTOCOL.md §5, and §14 for the keys): one edit, undo or redo, an
// EditBatch all or nothing, a second morph key; and the retraction of a
// command the server refuses after applying it. Its host calls it on its
// strand, in the order commands arrive, which is the document's version order.
#pragma once

#include <cstdint>
#include <vector>

#include "core/morph/keyed_document.h"
#include "core/util/status.h"
#include "protocol/tessera.pb.h"
#include "server/document/journal_entry.h"
#include "server/store/store.h"

namespace tessera::server {

// What one applied command (or batch) changed.
struct AppliedChange {
  JournalEntry entry;
  std::vector<uint64_t> editIds;     // per command: the edit made, undone or redone
  std::vector<VertexId> limits;      // every limit of key 0 the command(s) changed
  std::vector<VertexId> key1Limits;  // and of key 1 (a morph document's; all of them for AddMorphKey)
  uint32_t failedIndex = 0;          // an EditBatch's refused command, from 1; 0 otherwise
};

// Applies `message` to document `id`. On an error nothing of it stays
// applied (a batch's applied commands are taken back, newest first).
Status applyCommand(KeyedDocument& doc, store::DocumentId id, const wire::ClientMessage& message,
                    AppliedChange& applied);

// Takes an applied command back: its limits are restored bit for bit.
Status retractCommand(KeyedDocument& doc, const JournalEntry& entry);

}  // namespace tessera::server
