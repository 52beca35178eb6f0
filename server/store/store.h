// Store: where the server keeps everything that must survive a restart.
//
// Documents (name and the serialized version-0 document), the ordered edit
// journal, periodic snapshots and access tokens. Payloads are opaque bytes:
// the store never parses geometry, so it links no geometry code and another
// engine (PostgreSQL, per DESIGN.md) can replace the embedded SQLite one
// behind this interface.
//
// Durability contract: a write is acknowledged (a sync call returns ok, or an
// append's callback gets an ok Status) only once it is durable. A failed or
// unacknowledged write may be lost; an acknowledged one never is.
//
//   auto store = SqliteStore::open("/var/lib/tessera");
//   TESSERA_ASSIGN_OR_RETURN(DocumentId id, (*store)->createDocument("bracket", baseBytes));
//   (*store)->append(id, 1, "alice", editBytes, [](Status s) { /* ack or reject */ });
#pragma once

#include <chrono>
#include <compare>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/util/status.h"
#include "server/base/latency_histogram.h"

namespace tessera::store {

// Documents are numbered from 1 and numbers are never reused, so a stale id
// held by a client can never name a newer document.
struct DocumentId {
  uint64_t value = 0;
  auto operator<=>(const DocumentId&) const = default;
};

std::string toString(DocumentId id);  // "document 7": the form used in messages

// Ordered: a role can do everything the ones below it can.
enum class Role : uint8_t {
  kViewer = 1,  // reads and subscribes
  kEditor = 2,  // also edits
  kAdmin = 3,   // also creates and deletes documents and grants tokens
};

const char* roleName(Role role);                  // "viewer", "editor", "admin"
Expected<Role> parseRole(std::string_view name);  // the inverse of roleName

// What a token grants access to: one document, or every document (present
// and future). Documents never get id 0, so the two cannot collide.
class TokenScope {
 public:
  static TokenScope allDocuments() { return TokenScope(std::nullopt); }
  static TokenScope document(DocumentId id) { return TokenScope(id); }

  bool isAllDocuments() const { return !document_.has_value(); }
  DocumentId documentId() const { return document_.value_or(DocumentId{}); }
  std::string toString() const;  // "all documents" or "document 7"

 private:
  explicit TokenScope(std::optional<DocumentId> document) : document_(document) {}
  std::optional<DocumentId> document_;
};

struct DocumentSummary {
  DocumentId id;
  std::string name;
  uint64_t latestVersion = 0;  // 0: no edit yet
};

struct JournalEntry {
  uint64_t version = 0;  // contiguous from 1 per document
  std::string author;
  std::string bytes;  // one serialized command, opaque to the store
  // Which client command made it (its session and client_seq), where the
  // store keeps that (the cluster's: appendFrom); 0 otherwise.
  uint64_t authorSession = 0, clientSeq = 0;
};

struct Snapshot {
  uint64_t version = 0;  // the document state after entries 1..version
  std::string bytes;
};

// Everything needed to rebuild a document: base, then the snapshot if any,
// then `entries` (the journal after the snapshot, in version order).
struct StoredDocument {
  DocumentId id;
  std::string name;
  std::string baseBytes;  // the serialized document at version 0
  std::optional<Snapshot> snapshot;
  std::vector<JournalEntry> entries;

  uint64_t latestVersion() const;
};

struct StoreStats {
  uint64_t entriesCommitted = 0;                   // journal entries made durable
  uint64_t entriesRejected = 0;                    // appends refused or lost to a failed commit
  uint64_t batches = 0;                            // transactions committed (each with one fsync)
  uint64_t writesCommitted = 0;                    // appends and other writes (create, snapshot, ...)
  double averageBatchSize = 0;                     // writesCommitted / batches
  std::chrono::microseconds lastCommitLatency{0};  // BEGIN to durable COMMIT, last batch
  server::LatencyBuckets commitLatency;            // BEGIN to durable COMMIT, every batch
};

// What an acknowledged write survives in this store (docs/CLUSTER.md "What
// an acknowledged edit survives"), for the log, the stats and the metrics.
enum class WriteSync {
  kEachWrite,     // on disk (fsync) before the acknowledgement: SQLite
  kNotEachWrite,  // acknowledged from memory and the page cache: nats-server before 2.10
  kConfigured,    // per the NATS servers' sync_interval, which a node cannot read (2.10 and later)
};
const char* writeSyncName(WriteSync sync);  // "each-write", "not-each-write", "configured"

struct Durability {
  std::string backend;        // "sqlite", "nats" (or a test's)
  std::string engineVersion;  // SQLite's, or the NATS servers'
  WriteSync sync = WriteSync::kNotEachWrite;
  std::string statement;  // one sentence for people
};

// A failed write whose outcome the store cannot know (a replicated store's
// request timed out: the write may be stored), so that callers can tell it
// from a refusal. A store returns kTimeout for a write only in this case.
inline Status outcomeUnknownError(const std::string& why) {
  return timeoutError("outcome unknown: " + why);
}
inline bool outcomeUnknown(const Status& status) {
  return status.code() == ErrorCode::kTimeout;
}

// Called exactly once per append: ok once the entry is durable, otherwise why
// it was refused. Runs on the store's writer thread: keep it short, never
// block in it and never call a synchronous store method from it.
using AppendCallback = std::function<void(Status)>;

class Store {
 public:
  virtual ~Store() = default;

  // Documents. Unknown ids fail with kNotFound naming the id.
  virtual Expected<DocumentId> createDocument(std::string_view name, std::string_view baseBytes) = 0;
  virtual Expected<std::vector<DocumentSummary>> listDocuments() = 0;
  virtual Status deleteDocument(DocumentId id) = 0;  // with its journal, snapshots and tokens
  virtual Expected<StoredDocument> loadDocument(DocumentId id) = 0;

  // Journal. `version` must be exactly the document's latest version + 1 when
  // the append reaches the writer; otherwise only this append is refused.
  // Appends are committed in the order they were called.
  virtual void append(DocumentId id, uint64_t version, std::string author, std::string bytes,
                      AppendCallback done) = 0;
  virtual Status appendSync(DocumentId id, uint64_t version, std::string author, std::string bytes) = 0;
  // append(), also recording which client command made the entry, for
  // stores that keep it: in a cluster, a client whose document moved to
  // another node learns from it whether a command left unanswered was
  // applied (docs/CLUSTER.md). This default forgets the origin.
  virtual void appendFrom(DocumentId id, uint64_t version, std::string author, uint64_t authorSession,
                          uint64_t clientSeq, std::string bytes, AppendCallback done) {
    (void)authorSession;
    (void)clientSeq;
    append(id, version, std::move(author), std::move(bytes), std::move(done));
  }
  // Makes every later append by a writer that loaded the document before
  // this call fail (a cluster's new owner calls it after loading, so a
  // paused old owner cannot append after the load). A no-op where one
  // process is the only writer by construction (SQLite's directory lock).
  virtual Status fenceJournal(DocumentId id) {
    (void)id;
    return Status::ok();
  }

  // Snapshots: `version` must be in 1..latest. The newest two per document
  // are kept; loadDocument starts from the newest.
  virtual Status putSnapshot(DocumentId id, uint64_t version, std::string_view bytes) = 0;

  // Tokens. Only a SHA-256 hash of a token is stored, and no message ever
  // contains a token. Granting a token again for the same scope replaces its
  // role. roleFor returns the highest role the token holds for `scope` (an
  // all-documents grant counts for every document) or kNotFound.
  virtual Status addToken(TokenScope scope, std::string_view token, Role role) = 0;
  virtual Status revokeToken(std::string_view token) = 0;  // every grant of it
  virtual Expected<Role> roleFor(std::string_view token, TokenScope scope) = 0;
  // Whether any grant, for one document or all of them, names the token: a
  // Hello whose token is known nowhere is a failed authentication.
  virtual Expected<bool> knowsToken(std::string_view token) = 0;

  virtual StoreStats stats() const = 0;
  virtual Durability durability() const = 0;

  // Stops accepting writes, commits those already queued (their callbacks
  // are called), and releases the data directory. Idempotent; later calls
  // fail with kIoError.
  virtual void close() = 0;
};

}  // namespace tessera::store
