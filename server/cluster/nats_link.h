// NatsLink: one connection to a NATS cluster and its JetStream context, with
// NATS and JetStream errors turned into Status values that name the cluster
// and the operation. The cluster mode's store, leases and fan-out all talk to
// NATS through one link (docs/CLUSTER.md).
//
// NATS handles were made for C; the small owners below free them, so that no
// early return leaks one.
#pragma once

#include <nats/nats.h>

#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "core/util/status.h"

namespace tessera::cluster {

struct NatsLinkOptions {
  std::vector<std::string> urls;  // nats://host:port, tried in turn
  std::string clientName;         // shows in the NATS server's connection list
  // Connect, and each JetStream request. Above the few seconds JetStream
  // takes to elect a new stream leader when a NATS server dies, so a write
  // in flight then waits for it instead of failing with an unknown outcome.
  std::chrono::milliseconds timeout{6000};
};

// "nats://a:4222,nats://b:4222" -> {"nats://a:4222", "nats://b:4222"};
// refuses an empty list or a URL that is not nats://host:port.
Expected<std::vector<std::string>> parseNatsUrls(std::string_view list);

struct MsgDeleter {
  void operator()(natsMsg* m) const { natsMsg_Destroy(m); }
};
struct KvEntryDeleter {
  void operator()(kvEntry* e) const { kvEntry_Destroy(e); }
};
struct PubAckDeleter {
  void operator()(jsPubAck* a) const { jsPubAck_Destroy(a); }
};
struct SubscriptionDeleter {
  void operator()(natsSubscription* s) const { natsSubscription_Destroy(s); }
};
struct MetaDataDeleter {
  void operator()(jsMsgMetaData* m) const { jsMsgMetaData_Destroy(m); }
};
struct KvStoreDeleter {
  void operator()(kvStore* kv) const { kvStore_Destroy(kv); }
};
struct KvWatcherDeleter {
  void operator()(kvWatcher* w) const { kvWatcher_Destroy(w); }
};
using NatsMsgPtr = std::unique_ptr<natsMsg, MsgDeleter>;
using KvEntryPtr = std::unique_ptr<kvEntry, KvEntryDeleter>;
using PubAckPtr = std::unique_ptr<jsPubAck, PubAckDeleter>;
using SubscriptionPtr = std::unique_ptr<natsSubscription, SubscriptionDeleter>;
using MetaDataPtr = std::unique_ptr<jsMsgMetaData, MetaDataDeleter>;
using KvStorePtr = std::unique_ptr<kvStore, KvStoreDeleter>;
using KvWatcherPtr = std::unique_ptr<kvWatcher, KvWatcherDeleter>;

// How a JetStream stream or key-value bucket is made. Replicas > 1 needs a
// JetStream cluster of at least that many servers.
struct StreamSpec {
  std::string name;
  std::vector<std::string> subjects;
  int replicas = 1;
  int64_t maxMsgsPerSubject = -1;  // -1: unlimited
  int32_t maxMessageBytes = -1;
  // Lets every replica answer direct gets (reads that need no consumer and
  // no stream leader, so they keep working while a leader is re-elected).
  bool allowDirect = true;
};
struct BucketSpec {
  std::string name;
  int replicas = 1;
  std::chrono::milliseconds ttl{0};  // 0: values never expire
  int32_t maxValueBytes = -1;
};

class NatsLink {
 public:
  static Expected<std::unique_ptr<NatsLink>> connect(const NatsLinkOptions& options);
  ~NatsLink();
  NatsLink(const NatsLink&) = delete;
  NatsLink& operator=(const NatsLink&) = delete;

  natsConnection* connection() const { return connection_; }
  jsCtx* jetStream() const { return jetStream_; }
  const std::string& servers() const { return servers_; }  // for messages
  std::chrono::milliseconds timeout() const { return timeout_; }

  // Creates the stream or bucket, or opens it as it is when it exists (the
  // first node of a cluster creates them, the others find them). A bucket's
  // reads go to its stream's leader, so they see every acknowledged write.
  Status ensureStream(const StreamSpec& spec);
  // Called (on a NATS thread) each time the connection is back after a
  // loss: plain NATS messages published to this node meanwhile are gone.
  void onReconnected(std::function<void()> handler);
  Expected<KvStorePtr> ensureBucket(const BucketSpec& spec);
  // Takes the next value (from 1) of the counter under `key` in `bucket`, a
  // compare-and-set counter: two nodes taking at once never get the same
  // value, and no value is taken twice. `what` names it in errors.
  Expected<uint64_t> takeNext(kvStore* bucket, const std::string& key, std::string_view what);
  // The stream JetStream keeps a key-value bucket in ("KV_<bucket>").
  static std::string bucketStream(std::string_view bucket) { return "KV_" + std::string(bucket); }

  // A Status for a failed NATS call: "NATS (<servers>): <what>: <text>",
  // with JetStream's error code when there is one. Every failure is a
  // kIoError: the cluster, not the caller, is at fault.
  Status error(natsStatus status, std::string_view what, jsErrCode code = static_cast<jsErrCode>(0)) const;
  // Whether a failed call got no decision from JetStream (no answer, no
  // responder, no connection, or "JetStream system temporarily unavailable":
  // no quorum or no leader) rather than a refusal. What the caller asked for
  // may or may not have happened; with a refusal it did not. Call it on the
  // thread that made the call, before any other NATS call (it reads NATS's
  // per-thread last error).
  static bool undecided(natsStatus status, jsErrCode code = static_cast<jsErrCode>(0));

 private:
  NatsLink(std::string servers, std::chrono::milliseconds timeout)
      : servers_(std::move(servers)), timeout_(timeout) {}

  static void reconnected(natsConnection*, void* self);
  Expected<KvStorePtr> createOrOpenBucket(const BucketSpec& spec);

  natsConnection* connection_ = nullptr;
  jsCtx* jetStream_ = nullptr;
  std::mutex handlerMutex_;
  std::function<void()> reconnectedHandler_;
  std::string servers_;
  std::chrono::milliseconds timeout_;
};

}  // namespace tessera::cluster
