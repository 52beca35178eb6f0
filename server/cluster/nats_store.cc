#include "server/cluster/nats_store.h"

#include "server/cluster/nats_server_info.h"

#include <algorithm>
#include <future>
#include <string>

#include "server/cluster/journal_message.h"
#include "server/cluster/nats_blobs.h"
#include "server/store/store_checks.h"

namespace tessera::cluster {

namespace {

const std::string kJournalStream = "TESSERA_JOURNAL";
const std::string kBlobStream = "TESSERA_BLOBS";
constexpr size_t kRecentSequences = 4096;  // versions whose sequence a snapshot may need

std::string journalSubject(store::DocumentId id) {
  return "tessera.journal." + std::to_string(id.value);
}
std::string blobPrefix(store::DocumentId id) {
  return "tessera.blob." + std::to_string(id.value);
}
std::string catalogKey(store::DocumentId id) {
  return "doc." + std::to_string(id.value);
}

// The snapshots list on tessera.blob.<id>.snaps: newest first.
struct SnapshotRef {
  uint64_t version = 0, sequence = 0;
};
std::string encodeSnapshotRefs(const std::vector<SnapshotRef>& refs) {
  std::string out;
  for (const auto& r : refs) out += std::to_string(r.version) + " " + std::to_string(r.sequence) + "\n";
  return out;
}
std::vector<SnapshotRef> decodeSnapshotRefs(const std::string& text) {
  std::vector<SnapshotRef> refs;
  size_t at = 0;
  while (at < text.size()) {
    const size_t end = text.find('\n', at);
    const std::string line = text.substr(at, end == std::string::npos ? std::string::npos : end - at);
    SnapshotRef r;
    if (std::sscanf(line.c_str(), "%lu %lu", &r.version, &r.sequence) == 2) refs.push_back(r);
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return refs;
}

}  // namespace

namespace {

// The weakest guarantee among the NATS servers that answer: an acknowledged
// write is as durable as the servers that hold it.
store::Durability durabilityOf(const std::vector<std::string>& urls) {
  std::optional<NatsServerInfo> weakest;
  for (const std::string& url : urls) {
    auto info = readNatsServerInfo(url, std::chrono::milliseconds(2000));
    if (!info.isOk()) continue;
    if (!weakest || (supportsPerWriteSync(weakest->version) && !supportsPerWriteSync(info->version)))
      weakest = *info;
  }
  if (!weakest) {
    return {
        "nats", "unknown", store::WriteSync::kNotEachWrite,
        "no NATS server told its version: acknowledged writes are taken to be in memory and the page cache"};
  }
  return natsDurability(*weakest);
}

}  // namespace

Expected<std::unique_ptr<NatsStore>> NatsStore::open(const NatsStoreOptions& options) {
  TESSERA_ASSIGN_OR_RETURN(std::unique_ptr<NatsLink> link, NatsLink::connect(options.link));
  TESSERA_RETURN_IF_ERROR(link->ensureStream(
      StreamSpec{.name = kJournalStream, .subjects = {"tessera.journal.*"}, .replicas = options.replicas}));
  TESSERA_RETURN_IF_ERROR(link->ensureStream(StreamSpec{.name = kBlobStream,
                                                        .subjects = {"tessera.blob.>"},
                                                        .replicas = options.replicas,
                                                        .maxMsgsPerSubject = 1}));
  TESSERA_ASSIGN_OR_RETURN(KvStorePtr catalog, link->ensureBucket(BucketSpec{.name = "TESSERA_CATALOG",
                                                                             .replicas = options.replicas}));
  TESSERA_ASSIGN_OR_RETURN(KvStorePtr tokens, link->ensureBucket(BucketSpec{.name = "TESSERA_TOKENS",
                                                                            .replicas = options.replicas}));
  std::unique_ptr<NatsStore> store(new NatsStore(std::move(link), std::move(catalog), std::move(tokens)));
  store->durability_ = durabilityOf(options.link.urls);
  return store;
}

NatsStore::NatsStore(std::unique_ptr<NatsLink> link, KvStorePtr catalog, KvStorePtr tokens)
    : link_(std::move(link)), catalog_(std::move(catalog)), tokens_(*link_, std::move(tokens)) {
  writer_ = std::thread([this] { run(); });
}

NatsStore::~NatsStore() {
  close();
}

void NatsStore::close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closing_) return;
    closing_ = true;
  }
  wake_.notify_all();
  if (writer_.joinable()) writer_.join();
  std::lock_guard<std::mutex> lock(mutex_);
  closed_ = true;
}

Status NatsStore::checkOpen() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (closing_) return ioError("NATS (" + link_->servers() + "): the store is closed");
  return Status::ok();
}

// ---- documents -------------------------------------------------------------

Expected<std::string> NatsStore::documentName(store::DocumentId id) {
  TESSERA_RETURN_IF_ERROR(store::checkDocumentId(id));
  kvEntry* raw = nullptr;
  const natsStatus s = kvStore_Get(&raw, catalog_.get(), catalogKey(id).c_str());
  KvEntryPtr entry(raw);
  if (s == NATS_NOT_FOUND) return store::documentNotFound(id);
  if (s != NATS_OK) return link_->error(s, "reading the catalogue entry of " + toString(id));
  return std::string(static_cast<const char*>(kvEntry_Value(entry.get())),
                     static_cast<size_t>(kvEntry_ValueLen(entry.get())));
}

Expected<store::DocumentId> NatsStore::createDocument(std::string_view name, std::string_view baseBytes) {
  TESSERA_RETURN_IF_ERROR(checkOpen());
  TESSERA_RETURN_IF_ERROR(store::checkDocumentName(name));
  // Ids come from a compare-and-set counter, so two nodes creating at once
  // never get the same id, and ids are never reused.
  TESSERA_ASSIGN_OR_RETURN(uint64_t next, link_->takeNext(catalog_.get(), "next-id", "document id"));
  const store::DocumentId id{next};
  // The base and the genesis message first, the catalogue entry last: a
  // document is listed only once it is whole.
  TESSERA_RETURN_IF_ERROR(putBlob(*link_, kBlobStream, blobPrefix(id) + ".base", baseBytes));
  const std::string genesis = encodeJournalMessage(JournalMessage{.fence = true});
  jsPubAck* ackRaw = nullptr;
  jsErrCode code = static_cast<jsErrCode>(0);
  natsStatus s = js_Publish(&ackRaw, link_->jetStream(), journalSubject(id).c_str(), genesis.data(),
                            static_cast<int>(genesis.size()), nullptr, &code);
  PubAckPtr ack(ackRaw);
  if (s != NATS_OK) return link_->error(s, "starting the journal of " + toString(id), code);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    tails_[id.value] = Tail{0, ack->Sequence, true, {}};  // the genesis message is a fence
  }
  uint64_t revision = 0;
  s = kvStore_Put(&revision, catalog_.get(), catalogKey(id).c_str(), name.data(),
                  static_cast<int>(name.size()));
  if (s != NATS_OK) return link_->error(s, "listing " + toString(id) + " in the catalogue");
  return id;
}

Expected<std::vector<store::DocumentSummary>> NatsStore::listDocuments() {
  TESSERA_RETURN_IF_ERROR(checkOpen());
  kvKeysList keys{};
  const natsStatus s = kvStore_Keys(&keys, catalog_.get(), nullptr);
  std::vector<uint64_t> ids;
  if (s == NATS_OK) {
    for (int i = 0; i < keys.Count; ++i) {
      const std::string key = keys.Keys[i];
      if (key.rfind("doc.", 0) == 0) ids.push_back(std::stoull(key.substr(4)));
    }
    kvKeysList_Destroy(&keys);
  } else if (s != NATS_NOT_FOUND) {  // an empty bucket is "not found"
    return link_->error(s, "listing the catalogue");
  }
  std::sort(ids.begin(), ids.end());
  std::vector<store::DocumentSummary> documents;
  for (uint64_t value : ids) {
    const store::DocumentId id{value};
    auto name = documentName(id);
    if (!name.isOk()) {
      if (name.status().code() == ErrorCode::kNotFound) continue;  // deleted meanwhile
      return name.status();
    }
    // From the last message alone: when that is a fence a late write
    // landed before (Tail::fence), a lower bound until the next owner
    // loads the document and fences it with the whole journal's version.
    TESSERA_ASSIGN_OR_RETURN(Tail tail, tailOf(id));
    documents.push_back(store::DocumentSummary{id, std::move(*name), tail.version});
  }
  return documents;
}

Status NatsStore::deleteDocument(store::DocumentId id) {
  TESSERA_RETURN_IF_ERROR(checkOpen());
  TESSERA_ASSIGN_OR_RETURN(std::string name, documentName(id));
  (void)name;
  // Out of the catalogue first: from then on the document does not exist
  // for any node, even if the deletions below are cut short.
  natsStatus s = kvStore_Delete(catalog_.get(), catalogKey(id).c_str());
  if (s != NATS_OK) return link_->error(s, "removing " + toString(id) + " from the catalogue");
  {
    std::lock_guard<std::mutex> lock(mutex_);
    tails_.erase(id.value);
    loadedTails_.erase(id.value);
    failedLoads_.erase(id.value);
  }
  TESSERA_RETURN_IF_ERROR(deleteMessagesOn(*link_, kJournalStream, journalSubject(id)));
  TESSERA_RETURN_IF_ERROR(deleteMessagesOn(*link_, kBlobStream, blobPrefix(id) + ".>"));
  return tokens_.revokeDocument(id);
}

Expected<NatsStore::Tail> NatsStore::tailOf(store::DocumentId id) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = tails_.find(id.value);
    if (it != tails_.end()) return it->second;
  }
  auto last = lastMessage(*link_, kJournalStream, journalSubject(id));
  if (!last.isOk()) {
    if (last.status().code() == ErrorCode::kNotFound) return store::documentNotFound(id);
    return last.status();
  }
  TESSERA_ASSIGN_OR_RETURN(JournalMessage message,
                           decodeJournalMessage(last->payload, toString(id) + ", stream sequence " +
                                                                   std::to_string(last->sequence)));
  Tail tail{message.version, last->sequence, message.fence, {}};
  std::lock_guard<std::mutex> lock(mutex_);
  return tails_.emplace(id.value, tail).first->second;
}

Expected<std::vector<store::JournalEntry>> NatsStore::readJournal(store::DocumentId id,
                                                                  uint64_t afterSequence,
                                                                  uint64_t afterVersion,
                                                                  uint64_t lastSequence) {
  // Direct gets, one per entry: no consumer to create, and any replica
  // answers, so a takeover reads the journal while the stream's leader is
  // still being elected. A replica may lag the tail read from the leader by
  // a few messages: those are asked for again, briefly.
  std::vector<store::JournalEntry> entries;
  const std::string subject = journalSubject(id);
  uint64_t from = afterSequence + 1, expected = afterVersion + 1;
  while (from <= lastSequence) {
    auto next = nextMessageOnReplicas(*link_, kJournalStream, subject, from);
    if (!next.isOk()) {
      if (next.status().code() == ErrorCode::kNotFound) {
        return ioError(toString(id) + ": the journal's replicas do not reach stream sequence " +
                       std::to_string(lastSequence) + " (" + next.status().message() + ")");
      }
      return next.status();
    }
    const std::string where = toString(id) + ", stream sequence " + std::to_string(next->sequence);
    TESSERA_ASSIGN_OR_RETURN(JournalMessage message, decodeJournalMessage(next->payload, where));
    if (!message.fence && message.version > afterVersion) {
      if (message.version != expected) {
        return parseError(where + ": journal entry version " + std::to_string(message.version) + " where " +
                          std::to_string(expected) + " was next");
      }
      entries.push_back(store::JournalEntry{message.version, std::move(message.author),
                                            std::move(message.bytes), message.authorSession,
                                            message.clientSeq});
      ++expected;
    }
    from = next->sequence + 1;
  }
  return entries;
}

Expected<store::StoredDocument> NatsStore::loadDocument(store::DocumentId id) {
  TESSERA_RETURN_IF_ERROR(checkOpen());
  store::StoredDocument document;
  document.id = id;
  TESSERA_ASSIGN_OR_RETURN(document.name, documentName(id));
  TESSERA_ASSIGN_OR_RETURN(document.baseBytes,
                           getBlob(*link_, kBlobStream, blobPrefix(id) + ".base", toString(id) + "'s base"));
  // Read afresh: the journal may have grown on another node since this one
  // last saw it (a takeover is exactly that case).
  {
    std::lock_guard<std::mutex> lock(mutex_);
    tails_.erase(id.value);
    // From here the appends still queued for it are the host's this node
    // dropped before loading it again: refused unwritten (run), so none
    // lands behind the load. One already being written may: the fence
    // refuses then (fenceJournal).
    ++loads_[id.value];
  }
  TESSERA_ASSIGN_OR_RETURN(Tail tail, tailOf(id));
  uint64_t fromSequence = 0, fromVersion = 0;
  auto refs = lastMessage(*link_, kBlobStream, blobPrefix(id) + ".snaps");
  if (refs.isOk()) {
    // The newest snapshot that reads whole; an older one if it does not.
    for (const SnapshotRef& ref : decodeSnapshotRefs(refs->payload)) {
      auto bytes = getBlob(*link_, kBlobStream, blobPrefix(id) + ".snap." + std::to_string(ref.version),
                           toString(id) + "'s snapshot at version " + std::to_string(ref.version));
      if (!bytes.isOk()) continue;
      document.snapshot = store::Snapshot{ref.version, std::move(*bytes)};
      fromSequence = ref.sequence;
      fromVersion = ref.version;
      break;
    }
  } else if (refs.status().code() != ErrorCode::kNotFound) {
    return refs.status();
  }
  TESSERA_ASSIGN_OR_RETURN(document.entries, readJournal(id, fromSequence, fromVersion, tail.sequence));
  // Every message up to the tail was read, so the entries are the truth. A
  // fence at the end may say less: a write that had timed out can land
  // just before it (checkNothingBeforeFence), and a load must still read
  // such a journal, and leave the right version for the next append and
  // fence (seen in tests/cluster/cluster_quorum_test.cc: every later load
  // of the document failed).
  if (tail.fence ? document.latestVersion() < tail.version : document.latestVersion() != tail.version) {
    return parseError(toString(id) + ": its journal ends at version " +
                      std::to_string(document.latestVersion()) + " but its last message is " +
                      (tail.fence ? "a fence at " : "") + "version " + std::to_string(tail.version));
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (tail.fence && document.latestVersion() > tail.version) {
    if (auto it = tails_.find(id.value); it != tails_.end() && it->second.sequence == tail.sequence) {
      it->second.version = document.latestVersion();
    }
  }
  loadedTails_[id.value] = tail.sequence;
  return document;
}

// ---- journal ---------------------------------------------------------------

void NatsStore::append(store::DocumentId id, uint64_t version, std::string author, std::string bytes,
                       store::AppendCallback done) {
  appendFrom(id, version, std::move(author), 0, 0, std::move(bytes), std::move(done));
}

void NatsStore::appendFrom(store::DocumentId id, uint64_t version, std::string author, uint64_t authorSession,
                           uint64_t clientSeq, std::string bytes, store::AppendCallback done) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!closing_) {
      queue_.push_back(PendingAppend{id, version, std::move(author), std::move(bytes), std::move(done),
                                     authorSession, clientSeq, loads_[id.value]});
      wake_.notify_one();
      return;
    }
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.entriesRejected;
  }
  done(ioError("NATS (" + link_->servers() + "): the store is closed"));
}

Status NatsStore::appendSync(store::DocumentId id, uint64_t version, std::string author, std::string bytes) {
  if (std::this_thread::get_id() == writer_.get_id()) {
    return internalError("NATS (" + link_->servers() +
                         "): a synchronous store call from a store callback would wait for itself");
  }
  auto promise = std::make_shared<std::promise<Status>>();
  std::future<Status> result = promise->get_future();
  append(id, version, std::move(author), std::move(bytes),
         [promise](Status status) { promise->set_value(std::move(status)); });
  return result.get();
}

void NatsStore::run() {
  while (true) {
    PendingAppend next;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return closing_ || !queue_.empty(); });
      if (queue_.empty()) return;  // closing, and every queued append is done
      next = std::move(queue_.front());
      queue_.pop_front();
      if (next.load != loads_[next.id.value]) {
        ++stats_.entriesRejected;
        lock.unlock();
        next.done(ioError(toString(next.id) + ": journal entry version " + std::to_string(next.version) +
                          " not written: this node loaded the document again after the write was queued "
                          "(its host was dropped)"));
        continue;
      }
      // After a failed append, the tail is read afresh (publishAfter), and
      // it may be another owner's whose versions happen to line up with
      // this host's: a later entry of the same load would then be written
      // on top of a history it was not made from (seen in the
      // fault-injection soak, docs/CLUSTER.md: refused commands that are in
      // the journal). Nothing of that load is written any more.
      if (auto failed = failedLoads_.find(next.id.value);
          failed != failedLoads_.end() && failed->second == next.load) {
        ++stats_.entriesRejected;
        lock.unlock();
        next.done(ioError(toString(next.id) + ": journal entry version " + std::to_string(next.version) +
                          " not written: an earlier journal write of this node's copy of the document "
                          "failed, and this entry follows it; load the document again"));
        continue;
      }
    }
    const auto start = std::chrono::steady_clock::now();
    Status status = publishEntry(next);
    const auto latency =
        std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (status.isOk()) {
        ++stats_.entriesCommitted;
        ++stats_.writesCommitted;
        ++stats_.batches;
        stats_.lastCommitLatency = latency;
        stats_.commitLatency.add(latency);
        stats_.averageBatchSize = 1;
      } else {
        ++stats_.entriesRejected;
      }
    }
    next.done(std::move(status));
  }
}

NatsStore::Published NatsStore::publishAfter(store::DocumentId id, const std::string& payload,
                                             uint64_t expectedSequence) {
  jsPubOptions options;
  jsPubOptions_Init(&options);
  options.ExpectLastSubjectSeq = expectedSequence;
  jsPubAck* raw = nullptr;
  Published published{NATS_OK, static_cast<jsErrCode>(0), 0};
  published.status = js_Publish(&raw, link_->jetStream(), journalSubject(id).c_str(), payload.data(),
                                static_cast<int>(payload.size()), &options, &published.code);
  PubAckPtr ack(raw);
  if (published.status == NATS_OK) {
    published.sequence = ack->Sequence;
  } else {
    // Whatever happened, what this store believes of the journal's end may
    // be wrong now: read it again next time.
    std::lock_guard<std::mutex> lock(mutex_);
    tails_.erase(id.value);
  }
  return published;
}

Status NatsStore::publishEntry(const PendingAppend& append) {
  const store::DocumentId id = append.id;
  TESSERA_RETURN_IF_ERROR(store::checkDocumentId(id));
  TESSERA_RETURN_IF_ERROR(store::checkVersion(id, append.version, "journal entry"));
  TESSERA_RETURN_IF_ERROR(store::checkAuthor(id, append.author));
  TESSERA_ASSIGN_OR_RETURN(Tail tail, tailOf(id));
  if (append.version != tail.version + 1) return store::versionNotNext(id, append.version, tail.version);
  const std::string payload = encodeJournalMessage(JournalMessage{.version = append.version,
                                                                  .author = append.author,
                                                                  .authorSession = append.authorSession,
                                                                  .clientSeq = append.clientSeq,
                                                                  .bytes = append.bytes});
  // tail.sequence > 0: the genesis message is there.
  const Published published = publishAfter(id, payload, tail.sequence);
  const natsStatus s = published.status;
  const jsErrCode code = published.code;
  if (s != NATS_OK) {
    {
      // A refusal the arguments earned (above) leaves the journal as this
      // host knows it; a publish that failed does not (run).
      std::lock_guard<std::mutex> lock(mutex_);
      failedLoads_[id.value] = append.load;
    }
    if (code == JSStreamWrongLastSequenceErr) {
      return ioError(toString(id) + ": journal entry version " + std::to_string(append.version) +
                     " refused: another writer appended to the document's journal after stream sequence " +
                     std::to_string(tail.sequence) + " (this node no longer owns it)");
    }
    // A timeout leaves the outcome unknown: the entry may be stored.
    const Status failed = link_->error(
        s, toString(id) + ": journal entry version " + std::to_string(append.version) + " not acknowledged",
        code);
    return store::outcomeUnknownError(failed.message());
  }
  std::lock_guard<std::mutex> lock(mutex_);
  Tail& t = tails_[id.value];
  t.version = append.version;
  t.sequence = published.sequence;
  t.recent.emplace_back(append.version, published.sequence);
  if (t.recent.size() > kRecentSequences) t.recent.pop_front();
  return Status::ok();
}

Status NatsStore::fenceJournal(store::DocumentId id) {
  TESSERA_RETURN_IF_ERROR(checkOpen());
  TESSERA_ASSIGN_OR_RETURN(Tail tail, tailOf(id));
  {
    // The fence goes right after what this node's last load read. An entry
    // stored since is not in the loaded document -- the queued write of a
    // host this node dropped, which its store still sends -- and a fence
    // after it would let the new host answer that command "not applied"
    // (seen in the fault-injection soak, docs/CLUSTER.md: refused commands
    // that are in the journal).
    std::lock_guard<std::mutex> lock(mutex_);
    auto loaded = loadedTails_.find(id.value);
    if (loaded != loadedTails_.end() && loaded->second != tail.sequence) {
      const uint64_t then = loaded->second;
      loadedTails_.erase(loaded);
      return ioError(toString(id) + ": its journal grew after this node loaded it (to stream sequence " +
                     std::to_string(tail.sequence) + " from " + std::to_string(then) +
                     "); load the document again");
    }
  }
  // Checked like an append: if anyone wrote since this store read the
  // journal's end, the fence is refused and the caller loads again.
  const std::string payload = encodeJournalMessage(JournalMessage{.fence = true, .version = tail.version});
  const Published published = publishAfter(id, payload, tail.sequence);
  const natsStatus s = published.status;
  const jsErrCode code = published.code;
  if (s != NATS_OK) {
    if (code == JSStreamWrongLastSequenceErr) {
      return ioError(toString(id) + ": another writer appended to the journal after stream sequence " +
                     std::to_string(tail.sequence) + " while this node loaded it");
    }
    return link_->error(s, "fencing the journal of " + toString(id), code);
  }
  const Status alone = checkNothingBeforeFence(id, tail.sequence, published.sequence);
  std::lock_guard<std::mutex> lock(mutex_);
  loadedTails_.erase(id.value);
  if (!alone.isOk()) {
    tails_.erase(id.value);
    return alone;
  }
  tails_[id.value].sequence = published.sequence;
  return Status::ok();
}

Status NatsStore::checkNothingBeforeFence(store::DocumentId id, uint64_t loadedTail, uint64_t fence) {
  // A write that timed out while the stream had no quorum stays in its
  // leader's Raft log, and may be committed when the quorum is back, after
  // this store read the journal's end. The expected-last-subject-sequence
  // check then passes (nats-server checks it when it proposes the fence,
  // against what it has applied), so the fence alone does not prove the
  // load whole. Raft commits in log order: once the fence is acknowledged,
  // such an entry is stored before it, and any replica that has the fence
  // has it too. So the first message after the loaded tail must be the
  // fence itself; anything else means the load missed an entry (seen in
  // tests/cluster/cluster_quorum_test.cc as a journal with one version
  // twice), and the caller loads again.
  auto first = nextMessageOnReplicas(*link_, kJournalStream, journalSubject(id), loadedTail + 1);
  if (!first.isOk()) {
    return ioError(toString(id) +
                   ": cannot confirm that nothing precedes the journal's fence at stream sequence " +
                   std::to_string(fence) + " (" + first.status().message() + "); load the document again");
  }
  if (first->sequence == fence) return Status::ok();
  return ioError(toString(id) + ": stream sequence " + std::to_string(first->sequence) +
                 " was stored after this node read the journal's end (" + std::to_string(loadedTail) +
                 ") and before its fence (" + std::to_string(fence) +
                 "): a write that had timed out landed late; load the document again");
}

Status NatsStore::putSnapshot(store::DocumentId id, uint64_t version, std::string_view bytes) {
  TESSERA_RETURN_IF_ERROR(checkOpen());
  TESSERA_RETURN_IF_ERROR(store::checkDocumentId(id));
  TESSERA_RETURN_IF_ERROR(store::checkVersion(id, version, "snapshot"));
  TESSERA_ASSIGN_OR_RETURN(Tail tail, tailOf(id));
  if (version > tail.version) return store::snapshotPastEnd(id, version, tail.version);
  // The stream sequence of entry `version` lets a load read the journal from
  // there; 0 (not known here) makes it read from the start and skip.
  uint64_t sequence = 0;
  if (version == tail.version) sequence = tail.sequence;
  for (const auto& [v, seq] : tail.recent) {
    if (v == version) sequence = seq;
  }
  const std::string prefix = blobPrefix(id) + ".snap." + std::to_string(version);
  TESSERA_RETURN_IF_ERROR(putBlob(*link_, kBlobStream, prefix, bytes));
  std::vector<SnapshotRef> refs;
  auto old = lastMessage(*link_, kBlobStream, blobPrefix(id) + ".snaps");
  if (old.isOk()) refs = decodeSnapshotRefs(old->payload);
  refs.erase(
      std::remove_if(refs.begin(), refs.end(), [&](const SnapshotRef& r) { return r.version == version; }),
      refs.end());
  refs.insert(refs.begin(), SnapshotRef{version, sequence});
  std::sort(refs.begin(), refs.end(),
            [](const SnapshotRef& a, const SnapshotRef& b) { return a.version > b.version; });
  std::vector<SnapshotRef> dropped;
  while (refs.size() > 2) {  // the newest two, as the SQLite store keeps
    dropped.push_back(refs.back());
    refs.pop_back();
  }
  const std::string list = encodeSnapshotRefs(refs);
  jsPubAck* raw = nullptr;
  jsErrCode code = static_cast<jsErrCode>(0);
  const std::string subject = blobPrefix(id) + ".snaps";
  natsStatus s = js_Publish(&raw, link_->jetStream(), subject.c_str(), list.data(),
                            static_cast<int>(list.size()), nullptr, &code);
  PubAckPtr ack(raw);
  if (s != NATS_OK) return link_->error(s, "listing the snapshot of " + toString(id), code);
  for (const SnapshotRef& r : dropped) {
    const std::string gone = blobPrefix(id) + ".snap." + std::to_string(r.version);
    // The manifest first: a reader then finds no blob there.
    TESSERA_RETURN_IF_ERROR(deleteMessagesOn(*link_, kBlobStream, gone));
    TESSERA_RETURN_IF_ERROR(deleteMessagesOn(*link_, kBlobStream, gone + ".*"));
  }
  return Status::ok();
}

// ---- tokens ----------------------------------------------------------------

Status NatsStore::addToken(store::TokenScope scope, std::string_view token, store::Role role) {
  TESSERA_RETURN_IF_ERROR(checkOpen());
  if (!scope.isAllDocuments()) {
    TESSERA_ASSIGN_OR_RETURN(std::string name, documentName(scope.documentId()));
    (void)name;
  }
  return tokens_.add(scope, token, role);
}

Status NatsStore::revokeToken(std::string_view token) {
  TESSERA_RETURN_IF_ERROR(checkOpen());
  return tokens_.revoke(token);
}

Expected<store::Role> NatsStore::roleFor(std::string_view token, store::TokenScope scope) {
  TESSERA_RETURN_IF_ERROR(checkOpen());
  return tokens_.roleFor(token, scope);
}

Expected<bool> NatsStore::knowsToken(std::string_view token) {
  TESSERA_RETURN_IF_ERROR(checkOpen());
  return tokens_.knows(token);
}

store::StoreStats NatsStore::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

}  // namespace tessera::cluster
