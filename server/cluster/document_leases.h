// Ownership leases: which node applies a document's commands (docs/CLUSTER.md, "One owner per document").
//
// One key per document, doc.<id> -> node name, in the key-value bucket
// TESSERA_LEASES whose values expire after the lease time (the bucket's
// max age). A node takes a free lease with a create (refused when the key
// exists), renews it with a compare-and-set update on the revision it
// holds, and gives it up with a delete. A node that stops renewing (dead,
// paused, cut off) loses it when it expires; another node then takes it.
//
// Leases decide who should write; they do not protect the journal on their
// own. A paused owner may wake up still believing it owns the document:
// the journal's expected-sequence check (nats_store.h) refuses its append.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "server/cluster/nats_link.h"
#include "server/store/store.h"

namespace tessera::cluster {

class DocumentLeases {
 public:
  static Expected<std::unique_ptr<DocumentLeases>> open(NatsLink& link, std::string node,
                                                        std::chrono::milliseconds leaseTime, int replicas);

  // This node's lease of `id`: true when taken or already held; false with
  // `owner` set when another node holds it. kIoError when NATS does not
  // answer, or when the lease is held under this node's own name but not
  // by this process (from before a restart, or expired while NATS had no
  // quorum): never an owner to forward to; `ownStale`, if given, is then
  // set: a refusal that ends by itself within the lease time.
  Expected<bool> acquire(store::DocumentId id, std::string* owner = nullptr, bool* ownStale = nullptr);
  // Renews a held lease. kNotFound: taken by another node or expired, this
  // node no longer owns the document. kIoError: NATS did not answer (no
  // quorum, disconnected): ownership is unknown but nobody can take it.
  Status renew(store::DocumentId id);
  // Gives the lease up (the document closed here); another node may take it at once.
  void release(store::DocumentId id);
  // Who holds the lease now, if anyone.
  Expected<std::optional<std::string>> ownerOf(store::DocumentId id);
  bool holds(store::DocumentId id) const;

  static constexpr const char* kBucket = "TESSERA_LEASES";

  const std::string& node() const { return node_; }
  std::chrono::milliseconds leaseTime() const { return leaseTime_; }

 private:
  DocumentLeases(NatsLink& link, KvStorePtr bucket, std::string node, std::chrono::milliseconds leaseTime)
      : link_(link), bucket_(std::move(bucket)), node_(std::move(node)), leaseTime_(leaseTime) {}

  NatsLink& link_;
  KvStorePtr bucket_;
  const std::string node_;
  const std::chrono::milliseconds leaseTime_;
  using Clock = std::chrono::steady_clock;
  struct Held {
    uint64_t revision = 0;      // of our key, for the compare-and-set renewal
    Clock::time_point renewed;  // when the last renewal that succeeded was sent
    // A renewal since then got no decision from NATS: if the lease is then
    // found expired, that is why (a cluster without quorum), and it is said.
    bool undecidedSince = false;
  };
  mutable std::mutex mutex_;
  std::map<uint64_t, Held> held_;  // by document
};

}  // namespace tessera::cluster
