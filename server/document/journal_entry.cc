#include "server/document/journal_entry.h"

#include "core/document/edit_codec.h"
#include "core/util/byte_io.h"

namespace tessera::server {

namespace {

// A batch holds at most this many entries: the protocol's EditBatch limit,
// with room; a larger count is a damaged entry, not an allocation to try.
constexpr uint32_t kMaxBatchEntries = 1u << 16;
// On the wire only: an edit, undo or redo on a key other than 0 is this
// byte and the key, then the entry itself (entries of key 0 are written as
// they always were).
constexpr uint8_t kOnKey = 6;

void writeEntry(const JournalEntry& entry, ByteWriter& w) {
  if (entry.key != 0) {
    w.put<uint8_t>(kOnKey);
    w.put<uint32_t>(entry.key);
  }
  w.put<uint8_t>(static_cast<uint8_t>(entry.kind));
  switch (entry.kind) {
    case JournalEntry::Kind::kEdit:
      writeEdit(entry.edit, w);
      break;
    case JournalEntry::Kind::kUndo:
    case JournalEntry::Kind::kRedo:
      w.put<uint64_t>(entry.target.value);
      break;
    case JournalEntry::Kind::kBatch:
      w.put<uint32_t>(static_cast<uint32_t>(entry.batch.size()));
      for (const JournalEntry& part : entry.batch) writeEntry(part, w);
      break;
    case JournalEntry::Kind::kAddKey:
      w.put<uint32_t>(static_cast<uint32_t>(entry.keyPoints.size()));
      for (const Vec3& p : entry.keyPoints) {
        for (int c = 0; c < 3; ++c) w.put<double>(p[c]);
      }
      for (const std::string* image : {&entry.images.from, &entry.images.to}) {
        w.put<uint64_t>(image->size());
        w.putBytes(*image);
      }
      break;
  }
}

Status readEntry(ByteReader& r, const std::string& source, bool inBatch, JournalEntry& entry) {
  uint8_t kind = 0;
  TESSERA_RETURN_IF_ERROR(r.get(kind, "a journal entry kind"));
  if (kind == kOnKey) {
    TESSERA_RETURN_IF_ERROR(r.get(entry.key, "a morph key"));
    if (entry.key == 0 || entry.key >= kMaxMorphKeys) {
      return parseError(source + ": an entry on morph key " + std::to_string(entry.key));
    }
    TESSERA_RETURN_IF_ERROR(r.get(kind, "a journal entry kind"));
    const auto inner = static_cast<JournalEntry::Kind>(kind);
    if (inner != JournalEntry::Kind::kEdit && inner != JournalEntry::Kind::kUndo &&
        inner != JournalEntry::Kind::kRedo) {
      return parseError(source + ": a journal entry of kind " + std::to_string(kind) + " on a morph key");
    }
  }
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
    case JournalEntry::Kind::kAddKey: {
      if (inBatch) return parseError(source + ": a second morph key inside a batch");
      entry.kind = JournalEntry::Kind::kAddKey;
      uint32_t count = 0;
      TESSERA_RETURN_IF_ERROR(r.getCount(count, 3 * sizeof(double), "the second key's point count"));
      entry.keyPoints.resize(count);
      for (Vec3& p : entry.keyPoints) {
        for (int c = 0; c < 3; ++c) TESSERA_RETURN_IF_ERROR(r.get(p[c], "a point of the second key"));
      }
      for (std::string* image : {&entry.images.from, &entry.images.to}) {
        uint64_t size = 0;
        TESSERA_RETURN_IF_ERROR(r.get(size, "an image size"));
        if (size > r.remaining())
          return parseError(source + ": an image of " + std::to_string(size) + " bytes is truncated");
        TESSERA_RETURN_IF_ERROR(r.getBytes(*image, static_cast<size_t>(size), "an image"));
      }
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

Status applyJournalEntry(KeyedDocument& doc, const JournalEntry& entry) {
  if (entry.kind == JournalEntry::Kind::kBatch) {
    for (const JournalEntry& part : entry.batch) TESSERA_RETURN_IF_ERROR(applyJournalEntry(doc, part));
    return Status::ok();
  }
  if (entry.kind == JournalEntry::Kind::kAddKey) return doc.addKey(entry.keyPoints, entry.images);
  TESSERA_ASSIGN_OR_RETURN(Document * key, doc.editKey(entry.key));
  switch (entry.kind) {
    case JournalEntry::Kind::kEdit:
      return key->replay(entry.edit);
    case JournalEntry::Kind::kUndo:
      return key->undo(entry.target);
    case JournalEntry::Kind::kRedo:
      return key->redo(entry.target);
    default:
      break;
  }
  return invalidArgument("unknown journal entry kind");
}

}  // namespace tessera::server
