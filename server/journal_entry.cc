#include "server/journal_entry.h"

#include "core/document/edit_codec.h"
#include "core/util/byte_io.h"

namespace tessera::server {

namespace {

// A batch holds at most this many entries: the protocol's EditBatch limit,
// with room; a larger count is a damaged entry, not an allocation to try.
constexpr uint32_t kMaxBatchEntries = 1u << 16;

void writeEntry(const JournalEntry& entry, ByteWriter& w) {
  w.put<uint8_t>(static_cast<uint8_t>(entry.kind));
  switch (entry.kind) {
    case JournalEntry::Kind::kEdit: writeEdit(entry.edit, w); break;
    case JournalEntry::Kind::kUndo:
    case JournalEntry::Kind::kRedo: w.put<uint64_t>(entry.target.value); break;
    case JournalEntry::Kind::kBatch:
      w.put<uint32_t>(static_cast<uint32_t>(entry.batch.size()));
      for (const JournalEntry& part : entry.batch) writeEntry(part, w);
      break;
  }
}

Status readEntry(ByteReader& r, const std::string& source, bool inBatch, JournalEntry& entry) {
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
    case JournalEntry::Kind::kBatch: {
      if (inBatch) return parseError(source + ": a batch inside a batch");
      entry.kind = JournalEntry::Kind::kBatch;
      uint32_t count = 0;
      TESSERA_RETURN_IF_ERROR(r.get(count, "a batch's entry count"));
      if (count == 0 || count > kMaxBatchEntries) {
        return parseError(source + ": a batch of " + std::to_string(count) + " entries");
      }
      entry.batch.resize(count);
      for (JournalEntry& part : entry.batch) TESSERA_RETURN_IF_ERROR(readEntry(r, source, true, part));
      break;
    }
    default:
      return parseError(source + ": unknown journal entry kind " + std::to_string(kind));
  }
  return Status::ok();
}

}  // namespace

std::string encodeJournalEntry(const JournalEntry& entry) {
  ByteWriter w;
  writeEntry(entry, w);
  return std::move(w.bytes());
}

Expected<JournalEntry> decodeJournalEntry(std::string_view bytes, const std::string& source) {
  ByteReader r(bytes.data(), bytes.size(), source);
  JournalEntry entry;
  TESSERA_RETURN_IF_ERROR(readEntry(r, source, false, entry));
  if (r.remaining() != 0) return parseError(source + ": trailing bytes after the journal entry");
  return entry;
}

Status applyJournalEntry(Document& doc, const JournalEntry& entry) {
  switch (entry.kind) {
    case JournalEntry::Kind::kEdit: return doc.replay(entry.edit);
    case JournalEntry::Kind::kUndo: return doc.undo(entry.target);
    case JournalEntry::Kind::kRedo: return doc.redo(entry.target);
    case JournalEntry::Kind::kBatch:
      for (const JournalEntry& part : entry.batch) TESSERA_RETURN_IF_ERROR(applyJournalEntry(doc, part));
      return Status::ok();
  }
  return invalidArgument("unknown journal entry kind");
}

}  // namespace tessera::server
