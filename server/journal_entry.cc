#include "server/journal_entry.h"

#include "core/document/edit_codec.h"
#include "core/util/byte_io.h"

namespace tessera::server {

std::string encodeJournalEntry(const JournalEntry& entry) {
  ByteWriter w;
  w.put<uint8_t>(static_cast<uint8_t>(entry.kind));
  if (entry.kind == JournalEntry::Kind::kEdit) {
    writeEdit(entry.edit, w);
  } else {
    w.put<uint64_t>(entry.target.value);
  }
  return std::move(w.bytes());
}

Expected<JournalEntry> decodeJournalEntry(std::string_view bytes, const std::string& source) {
  ByteReader r(bytes.data(), bytes.size(), source);
  JournalEntry entry;
  uint8_t kind = 0;
  TESSERA_RETURN_IF_ERROR(r.get(kind, "a journal entry kind"));
  switch (static_cast<JournalEntry::Kind>(kind)) {
    case JournalEntry::Kind::kEdit: {
      entry.kind = JournalEntry::Kind::kEdit;
      TESSERA_ASSIGN_OR_RETURN(entry.edit, readEdit(r));
      break;
    }
    case JournalEntry::Kind::kUndo:
    case JournalEntry::Kind::kRedo:
      entry.kind = static_cast<JournalEntry::Kind>(kind);
      TESSERA_RETURN_IF_ERROR(r.get(entry.target.value, "an edit id"));
      break;
    default:
      return parseError(source + ": unknown journal entry kind " + std::to_string(kind));
  }
  if (r.remaining() != 0) return parseError(source + ": trailing bytes after the journal entry");
  return entry;
}

Status applyJournalEntry(Document& doc, const JournalEntry& entry) {
  switch (entry.kind) {
    case JournalEntry::Kind::kEdit: return doc.replay(entry.edit);
    case JournalEntry::Kind::kUndo: return doc.undo(entry.target);
    case JournalEntry::Kind::kRedo: return doc.redo(entry.target);
  }
  return invalidArgument("unknown journal entry kind");
}

}  // namespace tessera::server
