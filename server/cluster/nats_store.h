// NatsStore: the Store of the cluster mode, on NATS JetStream (docs/CLUSTER.md).
// Every node of a cluster opens one on the same NATS cluster and sees the
// same documents, journal and tokens (docs/CLUSTER.md, "What is stored where"):
//
//   stream TESSERA_JOURNAL   tessera.journal.<id>: one message per journal
//                            entry (journal_message.h), replicas R
//   stream TESSERA_BLOBS     tessera.blob.<id>.base and .snap.<version>:
//                            chunked blobs (nats_blobs.h); .snaps lists the
//                            newest two snapshots; one message per subject
//   bucket TESSERA_CATALOG   next-id, doc.<id> -> name
//   bucket TESSERA_TOKENS    <sha256 hex>.all / <sha256 hex>.doc<id> -> role
//
// Durability: an append is acknowledged once JetStream acknowledged its
// message, i.e. once a quorum of the stream's replicas stored it.
//
// One writer per document: every append carries
// Nats-Expected-Last-Subject-Sequence, the stream sequence of the document's
// last message as this store knows it. If another node appended meanwhile
// (it took the document over), JetStream refuses the append, and the store
// refuses it with a kIoError that says another writer appended; the host
// then stops serving the document (docs/CLUSTER.md, "One owner per document"). No version can be written
// twice, whatever the nodes believe. Once an append of a load of the
// document has failed, the rest of that load's appends are refused
// unwritten: they were made on top of it.
//
// Appends are published in the order they were called, each after the
// previous one's acknowledgement, by one writer thread whose callbacks run
// on it (the Store contract).
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "server/cluster/nats_link.h"
#include "server/cluster/nats_tokens.h"
#include "server/store/store.h"

namespace tessera::cluster {

struct NatsStoreOptions {
  NatsLinkOptions link;
  int replicas = 1;  // of every stream and bucket; 3 in a 3-node NATS cluster
};

class NatsStore final : public store::Store {
 public:
  // Connects and creates the streams and buckets when they do not exist.
  static Expected<std::unique_ptr<NatsStore>> open(const NatsStoreOptions& options);
  ~NatsStore() override;

  Expected<store::DocumentId> createDocument(std::string_view name, std::string_view baseBytes) override;
  Expected<std::vector<store::DocumentSummary>> listDocuments() override;
  Status deleteDocument(store::DocumentId id) override;
  Expected<store::StoredDocument> loadDocument(store::DocumentId id) override;

  void append(store::DocumentId id, uint64_t version, std::string author, std::string bytes,
              store::AppendCallback done) override;
  Status appendSync(store::DocumentId id, uint64_t version, std::string author, std::string bytes) override;
  void appendFrom(store::DocumentId id, uint64_t version, std::string author, uint64_t authorSession,
                  uint64_t clientSeq, std::string bytes, store::AppendCallback done) override;
  Status fenceJournal(store::DocumentId id) override;

  Status putSnapshot(store::DocumentId id, uint64_t version, std::string_view bytes) override;

  Status addToken(store::TokenScope scope, std::string_view token, store::Role role) override;
  Status revokeToken(std::string_view token) override;
  Expected<store::Role> roleFor(std::string_view token, store::TokenScope scope) override;
  Expected<bool> knowsToken(std::string_view token) override;

  store::StoreStats stats() const override;
  store::Durability durability() const override { return durability_; }
  void close() override;

  NatsLink& link() { return *link_; }

 private:
  // The last journal message of a document as this store knows it.
  struct Tail {
    uint64_t version = 0;
    uint64_t sequence = 0;  // its stream sequence, for the expected-sequence check
    // The last message is a fence: its version is the one its writer had
    // loaded, a lower bound (journal_message.h); loadDocument sets the
    // version from the entries it reads.
    bool fence = false;
    std::deque<std::pair<uint64_t, uint64_t>> recent;  // (version, sequence), for snapshots
  };
  struct PendingAppend {
    store::DocumentId id;
    uint64_t version;
    std::string author, bytes;
    store::AppendCallback done;
    uint64_t authorSession = 0, clientSeq = 0;
    uint64_t load = 0;  // loads_[id] when it was queued
  };

  NatsStore(std::unique_ptr<NatsLink> link, KvStorePtr catalog, KvStorePtr tokens);
  void run();  // the writer thread
  Status publishEntry(const PendingAppend& append);
  // Publishes `payload` on the journal of `id` only if the journal's last
  // message is still at `expectedSequence` (JetStream's expected last
  // subject sequence: an append and a fence are refused alike when another
  // node wrote since). On failure the cached tail is forgotten.
  struct Published {
    natsStatus status;
    jsErrCode code;
    uint64_t sequence;  // the message's stream sequence when published
  };
  Published publishAfter(store::DocumentId id, const std::string& payload, uint64_t expectedSequence);
  // The tail of a document, read from JetStream when not known; kNotFound
  // for a document that does not exist.
  Expected<Tail> tailOf(store::DocumentId id);
  // After a fence at `fence`: no message of the journal lies between the
  // tail the load read and the fence (nats_store.cc says why it could).
  Status checkNothingBeforeFence(store::DocumentId id, uint64_t loadedTail, uint64_t fence);
  Expected<std::string> documentName(store::DocumentId id);
  Expected<std::vector<store::JournalEntry>> readJournal(store::DocumentId id, uint64_t afterSequence,
                                                         uint64_t afterVersion, uint64_t lastSequence);
  Status checkOpen() const;

  std::unique_ptr<NatsLink> link_;
  KvStorePtr catalog_;
  NatsTokens tokens_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<PendingAppend> queue_;
  std::map<uint64_t, Tail> tails_;  // guarded by mutex_
  // Per document, the stream sequence its last load read to, until a fence
  // follows it (fenceJournal); guarded by mutex_.
  std::map<uint64_t, uint64_t> loadedTails_;
  // Per document, how many loads this store began: an append queued before
  // the latest began is a dropped host's, and is refused unwritten.
  std::map<uint64_t, uint64_t> loads_;  // guarded by mutex_
  // Per document, the load whose append JetStream did not take (refused,
  // or its outcome unknown): that load's later appends are refused
  // unwritten, since they follow a state the journal may not hold; guarded
  // by mutex_.
  std::map<uint64_t, uint64_t> failedLoads_;
  bool closing_ = false, closed_ = false;
  store::StoreStats stats_;
  store::Durability durability_;
  std::thread writer_;
};

}  // namespace tessera::cluster
