// What the server journals per document version: the edit made (exactly,
// offsets and all, so replay is bit for bit), an undo or redo, or a batch of
// them (an EditBatch: one version, one entry, so it is durable whole or not
// at all). Replaying the journal in version order onto the document's base
// rebuilds it. A morph document's second key is an entry too (kAddKey),
// and an edit, undo or redo names the key it is on (docs/PROTOCOL.md §14).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/document/document.h"
#include "core/hierarchy/edit.h"
#include "core/morph/keyed_document.h"
#include "core/util/status.h"

namespace tessera::server {

struct JournalEntry {
  enum class Kind : uint8_t { kEdit = 1, kUndo = 2, kRedo = 3, kBatch = 4, kAddKey = 5 };
  Kind kind = Kind::kEdit;
  Edit edit;                        // kEdit
  EditId target;                    // kUndo, kRedo
  std::vector<JournalEntry> batch;  // kBatch: edits, undos and redos (never a batch), in order
  uint32_t key = 0;                 // kEdit, kUndo, kRedo: the morph key they are on
  std::vector<Vec3> keyPoints;      // kAddKey: the second key's base points, exactly
  MorphImages images;               // kAddKey: a 2D morph's images (PNG), or none
};

std::string encodeJournalEntry(const JournalEntry& entry);
Expected<JournalEntry> decodeJournalEntry(std::string_view bytes, const std::string& source);
Status applyJournalEntry(KeyedDocument& doc, const JournalEntry& entry);

// A document's version after `journalEntries` journaled commands: 1 at
// creation, +1 per entry (docs/PROTOCOL.md on versions).
inline uint64_t documentVersionAfter(uint64_t journalEntries) {
  return journalEntries + 1;
}

}  // namespace tessera::server
