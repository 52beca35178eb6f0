#include "server/document/document_registry.h"

#include "core/morph/keyed_document_file.h"
#include "server/base/log.h"
#include "server/document/journal_entry.h"

namespace tessera::server {

namespace {

// The edit ids an entry's Ack carries: the edit made, undone or redone, or
// a batch's, one per command.
std::vector<uint64_t> editIdsOf(const JournalEntry& entry) {
  switch (entry.kind) {
    case JournalEntry::Kind::kEdit:
      return {entry.edit.id.value};
    case JournalEntry::Kind::kUndo:
    case JournalEntry::Kind::kRedo:
      return {entry.target.value};
    case JournalEntry::Kind::kBatch: {
      std::vector<uint64_t> ids;
      for (const JournalEntry& e : entry.batch) {
        for (uint64_t id : editIdsOf(e)) ids.push_back(id);
      }
      return ids;
    }
    case JournalEntry::Kind::kAddKey:
      return {};
  }
  return {};
}

// A stored document that cannot be read back is the server's failure, not
// a client's argument: its Reject gives REJECT_REASON_INTERNAL (replies.h).
Status unreadable(const Status& status) {
  return Status(ErrorCode::kInternal, status.message());
}

}  // namespace

Expected<std::shared_ptr<DocumentHost>> DocumentRegistry::open(store::DocumentId id) {
  std::lock_guard lock(mutex_);
  if (auto it = hosts_.find(id.value); it != hosts_.end()) {
    if (auto host = it->second.lock()) return host;
  }
  // The newest snapshot, then the journal after it, replayed exactly.
  TESSERA_ASSIGN_OR_RETURN(store::StoredDocument stored, store_.loadDocument(id));
  const std::string source = toString(id);
  const bool fromSnapshot = stored.snapshot.has_value();
  auto loaded = deserializeKeyedDocument(fromSnapshot ? stored.snapshot->bytes : stored.baseBytes, source);
  if (!loaded.isOk()) return unreadable(loaded.status());
  KeyedDocument doc = std::move(*loaded);
  uint64_t entries = fromSnapshot ? stored.snapshot->version : 0;
  const uint64_t loadedFrom = documentVersionAfter(entries);
  // Which client command made each replayed entry, where the store kept it
  // (the cluster's): a client whose document moved here asks.
  std::map<OutcomeBook::Key, CommandOutcome> outcomes;
  for (const auto& entry : stored.entries) {
    const std::string where = source + " journal entry " + std::to_string(entry.version);
    auto decoded = decodeJournalEntry(entry.bytes, where);
    if (!decoded.isOk()) return unreadable(decoded.status());
    if (Status replayed = applyJournalEntry(doc, *decoded); !replayed.isOk())
      return unreadable(replayed.withContext(where));
    entries = entry.version;
    if (entry.authorSession != 0) {
      CommandOutcome& o = outcomes[{entry.authorSession, entry.clientSeq}];
      o.version = documentVersionAfter(entry.version);
      o.editIds = editIdsOf(*decoded);
    }
  }
  auto host = std::make_shared<DocumentHost>(id, stored.name, std::move(doc), documentVersionAfter(entries),
                                             workers_, bulk_, store_, config_, stats_);
  if (!outcomes.empty()) host->setLoadedOutcomes(std::move(outcomes), loadedFrom);
  hosts_[id.value] = host;
  logEvent(LogLevel::kInfo, "document_loaded",
           {{"doc", id.value},
            {"version", documentVersionAfter(entries)},
            {"replayed", static_cast<uint64_t>(stored.entries.size())}});
  return host;
}

Expected<std::shared_ptr<DocumentEndpoint>> DocumentRegistry::openEndpoint(store::DocumentId id) {
  TESSERA_ASSIGN_OR_RETURN(std::shared_ptr<DocumentHost> host, open(id));
  return std::shared_ptr<DocumentEndpoint>(std::move(host));
}

int64_t DocumentRegistry::openCount() {
  std::lock_guard lock(mutex_);
  int64_t live = 0;
  for (auto it = hosts_.begin(); it != hosts_.end();) {
    if (it->second.expired()) {
      it = hosts_.erase(it);
    } else {
      ++live;
      ++it;
    }
  }
  return live;
}

void DocumentRegistry::forget(store::DocumentId id) {
  std::lock_guard lock(mutex_);
  hosts_.erase(id.value);
}

}  // namespace tessera::server
