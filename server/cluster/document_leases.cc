#include "server/cluster/document_leases.h"

namespace tessera::cluster {

namespace {

std::string leaseKey(store::DocumentId id) {
  return "doc." + std::to_string(id.value);
}

}  // namespace

Expected<std::unique_ptr<DocumentLeases>> DocumentLeases::open(NatsLink& link, std::string node,
                                                               std::chrono::milliseconds leaseTime,
                                                               int replicas) {
  TESSERA_ASSIGN_OR_RETURN(KvStorePtr bucket, link.ensureBucket(BucketSpec{
                                                  .name = kBucket, .replicas = replicas, .ttl = leaseTime}));
  return std::unique_ptr<DocumentLeases>(
      new DocumentLeases(link, std::move(bucket), std::move(node), leaseTime));
}

Expected<bool> DocumentLeases::acquire(store::DocumentId id, std::string* owner, bool* ownStale) {
  if (ownStale) *ownStale = false;
  if (holds(id)) return true;
  uint64_t revision = 0;
  const auto sent = Clock::now();
  natsStatus s = kvStore_CreateString(&revision, bucket_.get(), leaseKey(id).c_str(), node_.c_str());
  if (s == NATS_OK) {
    std::lock_guard<std::mutex> lock(mutex_);
    held_[id.value] = Held{.revision = revision, .renewed = sent};
    return true;
  }
  // Taken (or the create lost a race): who holds it?
  TESSERA_ASSIGN_OR_RETURN(std::optional<std::string> holder, ownerOf(id));
  if (!holder) return link_.error(s, "taking the lease of " + toString(id));
  if (*holder == node_) {
    // Under this node's name but not held here: a lease from before a
    // restart under the same name, or one that expired while NATS had no
    // quorum and that a replica still shows. Nobody writes meanwhile, which
    // is safe. It is no owner to forward to: the requests would come back
    // here to a document with no host, or, arriving late, to the host this
    // node loads next, and a late Leave would take a local session off it
    // (seen in tests/cluster/cluster_quorum_test.cc: the viewer got no more
    // deltas). So: no owner yet, and the caller tries again.
    if (ownStale) *ownStale = true;
    return ioError(toString(id) + ": its lease is still held under this node's name (" + node_ +
                   ") from before; it expires within the lease time");
  }
  if (owner) *owner = *holder;
  return false;
}

Status DocumentLeases::renew(store::DocumentId id) {
  Held held;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = held_.find(id.value);
    if (it == held_.end()) return notFound(toString(id) + ": no lease held by " + node_);
    held = it->second;
  }
  uint64_t next = 0;
  const auto sent = Clock::now();
  const natsStatus s =
      kvStore_UpdateString(&next, bucket_.get(), leaseKey(id).c_str(), node_.c_str(), held.revision);
  const bool undecided = s != NATS_OK && NatsLink::undecided(s);
  std::lock_guard<std::mutex> lock(mutex_);
  if (s == NATS_OK) {
    held_[id.value] = Held{.revision = next, .renewed = sent};
    return Status::ok();
  }
  const Status failed = link_.error(
      s, "renewing the lease of " + toString(id) + " (revision " + std::to_string(held.revision) + ")");
  if (undecided) {
    // NATS did not decide: nobody else can take the lease either (that
    // needs the same quorum), so the document stays here, read-only in
    // effect (its appends fail the same way).
    if (auto it = held_.find(id.value); it != held_.end()) it->second.undecidedSince = true;
    return failed;
  }
  held_.erase(id.value);
  std::string message = failed.message();
  const auto since = std::chrono::duration_cast<std::chrono::milliseconds>(sent - held.renewed);
  if (since > leaseTime_) {
    // The key expired (JetStream's max age), typically while NATS had no
    // quorum: a stream leader that lost its majority still expires keys
    // and then refuses the renewal with "wrong last sequence: 0".
    message += "; the lease had expired: last renewed " + std::to_string(since.count()) +
               " ms before, beyond the lease time of " + std::to_string(leaseTime_.count()) + " ms";
    if (held.undecidedSince) {
      message += ", and NATS decided none of the renewals since: is a majority of the NATS servers up?";
    }
  }
  return notFound(message);
}

void DocumentLeases::release(store::DocumentId id) {
  uint64_t revision = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = held_.find(id.value);
    if (it == held_.end()) return;
    revision = it->second.revision;
    held_.erase(it);
  }
  // Only our own lease: an update on our revision fails if another node
  // took the key meanwhile, and then the key is not ours to delete.
  uint64_t next = 0;
  if (kvStore_UpdateString(&next, bucket_.get(), leaseKey(id).c_str(), "", revision) == NATS_OK) {
    (void)kvStore_Delete(bucket_.get(), leaseKey(id).c_str());
  }
}

Expected<std::optional<std::string>> DocumentLeases::ownerOf(store::DocumentId id) {
  kvEntry* raw = nullptr;
  const natsStatus s = kvStore_Get(&raw, bucket_.get(), leaseKey(id).c_str());
  KvEntryPtr entry(raw);
  if (s == NATS_NOT_FOUND) return std::optional<std::string>();
  if (s != NATS_OK) return link_.error(s, "reading the lease of " + toString(id));
  std::string holder(static_cast<const char*>(kvEntry_Value(entry.get())),
                     static_cast<size_t>(kvEntry_ValueLen(entry.get())));
  if (holder.empty()) return std::optional<std::string>();  // being released
  return std::optional<std::string>(std::move(holder));
}

bool DocumentLeases::holds(store::DocumentId id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return held_.count(id.value) > 0;
}

}  // namespace tessera::cluster
