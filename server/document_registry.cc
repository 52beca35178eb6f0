#include "core/morph/keyed_document_file.h"
#include "server/journal_entry.h"
#include "server/log.h"
#include "server/server_context.h"

namespace tessera::server {

Expected<std::shared_ptr<DocumentHost>> DocumentRegistry::open(DocumentId id) {
  std::lock_guard lock(mutex_);
  if (auto it = hosts_.find(id.value); it != hosts_.end()) {
    if (auto host = it->second.lock()) return host;
  }
  // The newest snapshot, then the journal after it, replayed exactly.
  TESSERA_ASSIGN_OR_RETURN(StoredDocument stored, store_.loadDocument(id));
  const std::string source = toString(id);
  const bool fromSnapshot = stored.snapshot.has_value();
  TESSERA_ASSIGN_OR_RETURN(KeyedDocument doc,
                           deserializeKeyedDocument(fromSnapshot ? stored.snapshot->bytes : stored.baseBytes, source));
  uint64_t entries = fromSnapshot ? stored.snapshot->version : 0;
  for (const auto& entry : stored.entries) {
    const std::string where = source + " journal entry " + std::to_string(entry.version);
    TESSERA_ASSIGN_OR_RETURN(JournalEntry decoded, decodeJournalEntry(entry.bytes, where));
    TESSERA_RETURN_IF_ERROR(applyJournalEntry(doc, decoded).withContext(where));
    entries = entry.version;
  }
  auto host = std::make_shared<DocumentHost>(id, stored.name, std::move(doc), DocumentHost::versionOf(entries), workers_,
                                             bulk_, store_, config_, stats_);
  hosts_[id.value] = host;
  logEvent(LogLevel::kInfo, "document_loaded",
           {{"doc", id.value}, {"version", DocumentHost::versionOf(entries)}, {"replayed", static_cast<uint64_t>(stored.entries.size())}});
  return host;
}

Expected<std::shared_ptr<DocumentEndpoint>> DocumentRegistry::openEndpoint(DocumentId id) {
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

void DocumentRegistry::forget(DocumentId id) {
  std::lock_guard lock(mutex_);
  hosts_.erase(id.value);
}

}  // namespace tessera::server
