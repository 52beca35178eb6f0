// What the server journals per document version: the edit made (exactly,
// offsets and all, so replay is bit for bit), or an undo or redo. Replaying
// the journal in version order onto the document's base rebuilds it.
#pragma once

#include <string>
#include <string_view>

#include "core/document/document.h"
#include "core/document/edit.h"
#include "core/util/status.h"

namespace tessera::server {

struct JournalEntry {
  enum class Kind : uint8_t { kEdit = 1, kUndo = 2, kRedo = 3 };
  Kind kind = Kind::kEdit;
  Edit edit;      // kEdit
  EditId target;  // kUndo, kRedo
};

std::string encodeJournalEntry(const JournalEntry& entry);
Expected<JournalEntry> decodeJournalEntry(std::string_view bytes, const std::string& source);
Status applyJournalEntry(Document& doc, const JournalEntry& entry);

}  // namespace tessera::server
