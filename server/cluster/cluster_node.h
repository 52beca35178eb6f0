// A tessera-server node of a cluster (docs/CLUSTER.md): the
// document router of its connections, and its part in the cluster's traffic
// on plain NATS subjects:
//
//   tessera.node.<name>.forward   requests of other nodes' sessions for the
//                                 documents this node owns (Forward)
//   tessera.node.<name>.frames    what owners send to this node's sessions
//                                 (NodeMessage), fanned out here
//
// A monitor thread renews the leases of the documents this node owns
// (every third of the lease time) and watches the owners of the others;
// when an owner changes, the document's local sessions are moved
// (ClusterDocument::rehome). A message on these subjects that does not
// decode is logged and dropped; it never reaches a document.
#pragma once

#include <atomic>
#include <boost/asio/any_io_executor.hpp>
#include <chrono>
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "server/base/config.h"
#include "server/cluster/document_leases.h"
#include "server/cluster/message_chunks.h"
#include "server/cluster/nats_link.h"
#include "server/cluster/node_services.h"
#include "server/document/document_endpoint.h"

namespace tessera::cluster {

class ClusterDocument;

class ClusterNode : public server::DocumentOpener, public NodeServices {
 public:
  // Subscribes to the node's subjects and starts the lease monitor.
  static Expected<std::unique_ptr<ClusterNode>> start(NatsLink& link, store::Store& store,
                                                      server::DocumentRegistry& registry,
                                                      const server::ServerConfig& config,
                                                      server::ServerStats& stats,
                                                      boost::asio::any_io_executor workers);
  ~ClusterNode() override;

  Expected<std::shared_ptr<server::DocumentEndpoint>> openEndpoint(store::DocumentId id) override;
  void forget(store::DocumentId id) override;

  // Session ids of this node start here: the node's number (unique in the
  // cluster, from a counter in NATS) in the high bits, so a session id names
  // one session in the whole cluster (owners key participants by it).
  uint64_t firstSessionId() const { return number_ << 40; }
  std::vector<uint64_t> ownedDocuments();
  uint64_t messagesDropped() const { return dropped_.load(); }

  // NodeServices, for ClusterDocument.
  const std::string& name() const override { return name_; }
  uint32_t maxFrameBytes() const override { return config_.limits.maxFrameBytes; }
  DocumentLeases& leases() override { return *leases_; }
  server::DocumentRegistry& registry() override { return registry_; }
  server::ServerStats& stats() override { return stats_; }
  store::Store& store() override { return store_; }
  void forward(const std::string& owner, const Forward& request) override;
  void addLocalSession(uint64_t session, std::weak_ptr<server::Subscriber> who) override;
  void noteOutstanding(uint64_t session, uint64_t clientSeq, store::DocumentId document) override;
  std::vector<Outstanding> outstandingOf(
      store::DocumentId document, bool take,
      std::optional<std::chrono::steady_clock::time_point> askedBefore = {}) override;
  std::shared_ptr<RemoteSubscriber> remoteSubscriber(const std::string& node, uint64_t session) override;
  void pin(const std::shared_ptr<ClusterDocument>& document) override;
  void unpin(store::DocumentId id) override;
  void tellNotOwner(const std::string& node, store::DocumentId document, const std::string& owner) override;

 private:
  ClusterNode(NatsLink& link, store::Store& store, server::DocumentRegistry& registry,
              const server::ServerConfig& config, server::ServerStats& stats,
              boost::asio::any_io_executor workers, std::string name);
  static void onForward(natsConnection*, natsSubscription*, natsMsg* msg, void* self);
  static void onNodeMessage(natsConnection*, natsSubscription*, natsMsg* msg, void* self);
  // Both subscriptions: reassembles chunked messages, then hands each whole
  // one to `handle` (or drops it, logged, when its chunks are bad).
  void receive(natsMsg* msg, ChunkAssembler& chunks,
               void (ClusterNode::*handle)(const char*, int, const char*));
  std::shared_ptr<ClusterDocument> liveDocument(uint64_t id);  // null when not open here
  void handleForward(const char* data, int length, const char* subject);
  void handleNodeMessage(const char* data, int length, const char* subject);
  void dropMessage(const char* subject, int length, const std::string& why);
  // Other nodes' sessions that no longer take part in any document here
  // (they left, or their node is gone): their subscribers are dropped.
  void pruneRemoteSubscribers();
  void monitor();
  // Renews this node's key in TESSERA_ALIVE (name -> number, expiring after
  // the lease time) and drops other nodes' sessions whose node is gone or
  // came back as another incarnation: a dead node's viewers do not stay
  // on as participants.
  void heartbeat();
  // Renews this node's key in TESSERA_ALIVE from the revision it wrote
  // last. A refusal means the key lapsed meanwhile (a partition, NATS
  // without quorum): other nodes may have taken this node for gone and
  // dropped its sessions from the documents they own, so each document
  // this node does not own rejoins its sessions at the owner.
  void renewPresence();
  std::vector<std::shared_ptr<ClusterDocument>> liveDocuments();

  NatsLink& link_;
  store::Store& store_;
  server::DocumentRegistry& registry_;
  const server::ServerConfig& config_;
  server::ServerStats& stats_;
  const std::string name_;
  uint64_t number_ = 0;
  std::unique_ptr<DocumentLeases> leases_;
  KvStorePtr alive_;
  uint64_t aliveRevision_ = 0;  // of this node's key in TESSERA_ALIVE; the monitor's
  FrameRelay relay_;
  ChunkAssembler forwardChunks_, frameChunks_;  // messages larger than NATS's max_payload
  natsSubscription* forwardSubscription_ = nullptr;
  natsSubscription* framesSubscription_ = nullptr;

  std::mutex mutex_;
  std::map<uint64_t, std::weak_ptr<ClusterDocument>> documents_;
  std::map<uint64_t, std::shared_ptr<ClusterDocument>> pinned_;
  std::map<uint64_t, std::weak_ptr<server::Subscriber>> localSessions_;
  std::map<uint64_t, std::shared_ptr<RemoteSubscriber>> remoteSubscribers_;
  std::set<uint64_t> unjoinedBefore_;  // remote sessions no document held at the last prune
  struct BookEntry {
    uint64_t document = 0;
    std::chrono::steady_clock::time_point asked;  // when forwarded or last asked about
  };
  std::map<uint64_t, std::map<uint64_t, BookEntry>> outstanding_;  // session -> client_seq -> entry
  std::atomic<uint64_t> dropped_{0};
  std::atomic<bool> reconnected_{false};  // frames may have been lost: ask owners about outstanding commands

  std::mutex monitorMutex_;
  std::condition_variable monitorWake_;
  bool stopping_ = false;
  std::thread monitor_;
};

}  // namespace tessera::cluster
