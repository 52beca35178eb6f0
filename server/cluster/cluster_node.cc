#include "server/cluster/cluster_node.h"

#include <set>

#include "protocol/framing.h"
#include "server/base/log.h"
#include "server/cluster/cluster_document.h"
#include "server/cluster/message_chunks.h"

namespace tessera::cluster {

namespace {

// Node numbers come from a compare-and-set counter in the catalogue bucket,
// so two nodes never share one, even under the same name after a restart.
Expected<uint64_t> takeNodeNumber(NatsLink& link) {
  TESSERA_ASSIGN_OR_RETURN(KvStorePtr bucket,
                           link.ensureBucket(BucketSpec{.name = "TESSERA_NODES", .replicas = 1}));
  TESSERA_ASSIGN_OR_RETURN(uint64_t next, link.takeNext(bucket.get(), "next-number", "node number"));
  // 2^13 numbers: session ids stay below 2^53, exact in JavaScript too.
  return next % 8191 + 1;
}

}  // namespace

ClusterNode::ClusterNode(NatsLink& link, store::Store& store, server::DocumentRegistry& registry,
                         const server::ServerConfig& config, server::ServerStats& stats,
                         boost::asio::any_io_executor workers, std::string name)
    : link_(link),
      store_(store),
      registry_(registry),
      config_(config),
      stats_(stats),
      name_(std::move(name)),
      relay_(link, name_, workers) {}

Expected<std::unique_ptr<ClusterNode>> ClusterNode::start(NatsLink& link, store::Store& store,
                                                          server::DocumentRegistry& registry,
                                                          const server::ServerConfig& config,
                                                          server::ServerStats& stats,
                                                          boost::asio::any_io_executor workers) {
  std::string name = config.nodeName;
  for (char c : name) {
    // A node name is a NATS subject token and a key-value key part.
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')) {
      return invalidArgument("--node-name '" + name + "': use letters, digits, '-' and '_' only");
    }
  }
  std::unique_ptr<ClusterNode> node(
      new ClusterNode(link, store, registry, config, stats, workers, std::move(name)));
  TESSERA_ASSIGN_OR_RETURN(node->number_, takeNodeNumber(link));
  TESSERA_ASSIGN_OR_RETURN(node->leases_,
                           DocumentLeases::open(link, node->name_, std::chrono::milliseconds(config.leaseMs),
                                                config.clusterReplicas));
  TESSERA_ASSIGN_OR_RETURN(
      node->alive_, link.ensureBucket(BucketSpec{.name = "TESSERA_ALIVE",
                                                 .replicas = config.clusterReplicas,
                                                 // Three lease times: a node whose
                                                 // monitor was held up (a load, a busy
                                                 // machine) is not taken for dead; a dead
                                                 // node's sessions only go a little later.
                                                 .ttl = 3 * std::chrono::milliseconds(config.leaseMs)}));
  natsStatus s = kvStore_PutString(&node->aliveRevision_, node->alive_.get(), node->name_.c_str(),
                                   std::to_string(node->number_).c_str());
  if (s != NATS_OK) return link.error(s, "announcing node " + node->name_);
  s = natsConnection_Subscribe(&node->forwardSubscription_, link.connection(),
                               nodeSubject(node->name_, "forward").c_str(), &ClusterNode::onForward,
                               node.get());
  if (s == NATS_OK) {
    s = natsConnection_Subscribe(&node->framesSubscription_, link.connection(),
                                 nodeSubject(node->name_, "frames").c_str(), &ClusterNode::onNodeMessage,
                                 node.get());
  }
  if (s == NATS_OK) s = natsConnection_Flush(link.connection());
  if (s != NATS_OK) return link.error(s, "subscribing to node " + node->name_ + "'s subjects");
  stats.clusterNode = static_cast<int64_t>(node->number_);
  // Plain NATS messages to this node are lost while it is disconnected:
  // Acks among them. The monitor then asks the owners again.
  link.onReconnected([raw = node.get()] {
    raw->reconnected_ = true;
    raw->monitorWake_.notify_all();
  });
  node->monitor_ = std::thread([raw = node.get()] { raw->monitor(); });
  server::logEvent(server::LogLevel::kInfo, "cluster_node_started",
                   {{"node", node->name_},
                    {"number", node->number_},
                    {"nats", link.servers()},
                    {"lease_ms", static_cast<int64_t>(config.leaseMs)}});
  return node;
}

ClusterNode::~ClusterNode() {
  link_.onReconnected(nullptr);
  {
    std::lock_guard<std::mutex> lock(monitorMutex_);
    stopping_ = true;
  }
  monitorWake_.notify_all();
  if (monitor_.joinable()) monitor_.join();
  // No callback runs after these return.
  if (forwardSubscription_) {
    natsSubscription_Unsubscribe(forwardSubscription_);
    natsSubscription_Destroy(forwardSubscription_);
  }
  if (framesSubscription_) {
    natsSubscription_Unsubscribe(framesSubscription_);
    natsSubscription_Destroy(framesSubscription_);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  pinned_.clear();
}

Expected<std::shared_ptr<server::DocumentEndpoint>> ClusterNode::openEndpoint(store::DocumentId id) {
  std::shared_ptr<ClusterDocument> doc;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (auto it = documents_.find(id.value); it != documents_.end()) doc = it->second.lock();
    if (!doc) {
      // Registered at once, so that concurrent opens share it; one whose
      // load fails is dropped with its last opener (a weak entry).
      doc = std::make_shared<ClusterDocument>(id, *this);
      documents_[id.value] = doc;
    }
  }
  // Outside this node's lock: a document calls into the node under its own
  // lock (sessions, outstanding commands), so the node never waits for a
  // document while holding its lock; and a load from JetStream (seconds
  // when NATS is in trouble) stalls no other document's frames. A document
  // between owners (a takeover failed, e.g. on a damaged journal) is tried
  // again, so a new client hears why instead of waiting. Except when all
  // that stands in the way is this node's own lease from before (a restart,
  // or a lease NATS let lapse): that ends within the lease time, so the
  // session joins as the document's other sessions do and is served when
  // the monitor takes the document (ClusterDocument::rehome; docs/CLUSTER.md
  // "Fault-injection soak", finding 4).
  const Status resolved = doc->resolve();
  if (!resolved.isOk()) {
    if (!doc->ownerExpectedSoon()) return resolved;
    server::logEvent(server::LogLevel::kInfo, "document_awaits_own_lease",
                     {{"doc", id.value}, {"node", name_}, {"reason", resolved.message()}});
  }
  return std::shared_ptr<server::DocumentEndpoint>(doc);
}

void ClusterNode::forget(store::DocumentId id) {
  std::lock_guard<std::mutex> lock(mutex_);
  documents_.erase(id.value);
  pinned_.erase(id.value);
  registry_.forget(id);
}

std::vector<uint64_t> ClusterNode::ownedDocuments() {
  std::vector<uint64_t> owned;
  for (const auto& doc : liveDocuments()) {
    if (doc->ownedHere()) owned.push_back(doc->id().value);
  }
  return owned;
}

std::vector<std::shared_ptr<ClusterDocument>> ClusterNode::liveDocuments() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::shared_ptr<ClusterDocument>> live;
  for (auto it = documents_.begin(); it != documents_.end();) {
    if (auto doc = it->second.lock()) {
      live.push_back(std::move(doc));
      ++it;
    } else {
      it = documents_.erase(it);
    }
  }
  return live;
}

void ClusterNode::forward(const std::string& owner, const Forward& request) {
  const Status sent =
      publishMessage(link_, nodeSubject(owner, "forward"), name_, request.SerializeAsString());
  if (!sent.isOk()) {
    server::logEvent(server::LogLevel::kWarn, "cluster_forward_failed",
                     {{"to", owner}, {"doc", request.document_id()}, {"error", sent.message()}});
  }
}

void ClusterNode::noteOutstanding(uint64_t session, uint64_t clientSeq, store::DocumentId document) {
  std::lock_guard<std::mutex> lock(mutex_);
  outstanding_[session][clientSeq] = BookEntry{document.value, std::chrono::steady_clock::now()};
}

std::vector<ClusterNode::Outstanding> ClusterNode::outstandingOf(
    store::DocumentId document, bool take, std::optional<std::chrono::steady_clock::time_point> askedBefore) {
  const auto now = std::chrono::steady_clock::now();
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<Outstanding> found;
  for (auto it = outstanding_.begin(); it != outstanding_.end();) {
    const auto local = localSessions_.find(it->first);
    auto who = local != localSessions_.end() ? local->second.lock() : nullptr;
    Outstanding entry{who, {}};
    for (auto c = it->second.begin(); c != it->second.end();) {
      BookEntry& e = c->second;
      if (who && e.document == document.value && (!askedBefore || e.asked < *askedBefore)) {
        entry.clientSeqs.push_back(c->first);
        if (take) {
          c = it->second.erase(c);
          continue;
        }
        e.asked = now;
      }
      ++c;
    }
    if (!entry.clientSeqs.empty()) found.push_back(std::move(entry));
    // A closed session's entries go with the monitor's sweep of localSessions_.
    it = it->second.empty() ? outstanding_.erase(it) : std::next(it);
  }
  return found;
}

void ClusterNode::addLocalSession(uint64_t session, std::weak_ptr<server::Subscriber> who) {
  std::lock_guard<std::mutex> lock(mutex_);
  localSessions_[session] = std::move(who);
}

std::shared_ptr<RemoteSubscriber> ClusterNode::remoteSubscriber(const std::string& node, uint64_t session) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto& slot = remoteSubscribers_[session];
  if (!slot || slot->node() != node) slot = std::make_shared<RemoteSubscriber>(relay_, node, session);
  stats_.remoteSessions = static_cast<int64_t>(remoteSubscribers_.size());
  return slot;
}

void ClusterNode::tellNotOwner(const std::string& node, store::DocumentId document,
                               const std::string& owner) {
  NodeMessage message;
  message.mutable_not_owner()->set_document_id(document.value);
  message.mutable_not_owner()->set_owner(owner);
  relay_.publish(node, message);
}

void ClusterNode::pin(const std::shared_ptr<ClusterDocument>& document) {
  std::lock_guard<std::mutex> lock(mutex_);
  pinned_[document->id().value] = document;
}

void ClusterNode::unpin(store::DocumentId id) {
  std::shared_ptr<ClusterDocument> released;  // destroyed outside the lock
  std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = pinned_.find(id.value); it != pinned_.end()) {
    released = std::move(it->second);
    pinned_.erase(it);
  }
}

void ClusterNode::onForward(natsConnection*, natsSubscription*, natsMsg* msg, void* self) {
  auto* node = static_cast<ClusterNode*>(self);
  node->receive(msg, node->forwardChunks_, &ClusterNode::handleForward);
}

void ClusterNode::onNodeMessage(natsConnection*, natsSubscription*, natsMsg* msg, void* self) {
  auto* node = static_cast<ClusterNode*>(self);
  node->receive(msg, node->frameChunks_, &ClusterNode::handleNodeMessage);
}

void ClusterNode::receive(natsMsg* msg, ChunkAssembler& chunks,
                          void (ClusterNode::*handle)(const char*, int, const char*)) {
  const char* subject = natsMsg_GetSubject(msg);
  const int length = natsMsg_GetDataLength(msg);
  auto whole = chunks.add(std::string_view(natsMsg_GetData(msg), static_cast<size_t>(std::max(length, 0))));
  if (!whole.isOk()) {
    dropMessage(subject, length, whole.status().message());
  } else if (whole->has_value()) {
    (this->*handle)((*whole)->data(), static_cast<int>((*whole)->size()), subject);
  }
  natsMsg_Destroy(msg);
}

std::shared_ptr<ClusterDocument> ClusterNode::liveDocument(uint64_t id) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = documents_.find(id); it != documents_.end()) return it->second.lock();
  return nullptr;
}

void ClusterNode::dropMessage(const char* subject, int length, const std::string& why) {
  ++dropped_;
  ++stats_.clusterMessagesDropped;
  server::logEvent(
      server::LogLevel::kWarn, "cluster_message_dropped",
      {{"node", name_}, {"subject", subject}, {"bytes", static_cast<int64_t>(length)}, {"reason", why}});
}

void ClusterNode::handleForward(const char* data, int length, const char* subject) {
  Forward request;
  if (length <= 0 || !request.ParseFromArray(data, length))
    return dropMessage(subject, length, "not a cluster Forward");
  if (request.kind() == Forward::KIND_UNSPECIFIED || !Forward::Kind_IsValid(request.kind()) ||
      request.via_node().empty() || request.session_id() == 0 || request.document_id() == 0) {
    return dropMessage(subject, length, "a Forward without its kind, node, session or document");
  }
  auto doc = liveDocument(request.document_id());
  if (doc && doc->serveRemote(request)) return;
  if (request.kind() == Forward::KIND_LEAVE) return;  // nothing to leave here
  NodeMessage reply;
  reply.mutable_not_owner()->set_document_id(request.document_id());
  auto owner = leases_->ownerOf(store::DocumentId{request.document_id()});
  if (owner.isOk() && owner->has_value()) reply.mutable_not_owner()->set_owner(**owner);
  relay_.publish(request.via_node(), reply);
}

void ClusterNode::handleNodeMessage(const char* data, int length, const char* subject) {
  NodeMessage message;
  if (length <= 0 || !message.ParseFromArray(data, length))
    return dropMessage(subject, length, "not a cluster NodeMessage");
  if (message.has_not_owner()) {
    if (auto doc = liveDocument(message.not_owner().document_id())) {
      doc->markNotOwner();
      monitorWake_.notify_all();
    }
    return;
  }
  if (!message.has_frames()) return dropMessage(subject, length, "an empty cluster NodeMessage");
  auto outgoing = framesToOutgoing(message.frames(), config_.limits.maxFrameBytes);
  if (!outgoing.isOk()) return dropMessage(subject, length, outgoing.status().message());
  // An Ack or Reject answers a forwarded command: it is no longer outstanding.
  uint64_t answered = 0;
  const Frames& f = message.frames();
  if (!f.is_delta() && f.snapshot_of() == 0 && f.presence_of() == 0) {
    wire::ServerMessage reply;
    if (reply.ParseFromArray(f.frame().data() + kFrameHeaderBytes,
                             static_cast<int>(f.frame().size() - kFrameHeaderBytes))) {
      if (reply.has_ack()) answered = reply.ack().client_seq();
      if (reply.has_reject()) answered = reply.reject().client_seq();
    }
  }
  std::vector<std::shared_ptr<server::Subscriber>> targets;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (uint64_t session : message.frames().session_ids()) {
      if (answered != 0) {
        if (auto it = outstanding_.find(session); it != outstanding_.end()) {
          it->second.erase(answered);
          if (it->second.empty()) outstanding_.erase(it);
        }
      }
      auto it = localSessions_.find(session);
      if (it == localSessions_.end()) continue;
      if (auto who = it->second.lock()) targets.push_back(std::move(who));
    }
  }
  for (auto& who : targets) who->send(*outgoing);
}

void ClusterNode::renewPresence() {
  const std::string number = std::to_string(number_);
  uint64_t revision = 0;
  natsStatus s = kvStore_UpdateString(&revision, alive_.get(), name_.c_str(), number.c_str(), aliveRevision_);
  if (s == NATS_OK) {
    aliveRevision_ = revision;
    return;
  }
  // NATS did not decide: the key is as it was, or lapsed; the next renewal
  // tells.
  if (NatsLink::undecided(s)) return;
  // Refused: the key is not the one this node wrote last. Either an
  // undecided renewal landed after all (the key holds this incarnation at
  // a newer revision), or the key expired: nothing else writes or removes
  // it. While it was missing an owner may have taken this node for gone
  // (heartbeat) and dropped its sessions, after which the owner sends them
  // nothing (seen in the fault-injection soak, docs/CLUSTER.md: a viewer of
  // a partitioned node got no update after the partition healed).
  kvEntry* raw = nullptr;
  s = kvStore_Get(&raw, alive_.get(), name_.c_str());
  KvEntryPtr entry(raw);
  if (s == NATS_OK && number == kvEntry_ValueString(entry.get())) {
    aliveRevision_ = kvEntry_Revision(entry.get());
    return;
  }
  if (s != NATS_OK && s != NATS_NOT_FOUND) return;  // NATS unavailable: the next renewal tells
  s = kvStore_PutString(&revision, alive_.get(), name_.c_str(), number.c_str());
  if (s != NATS_OK) return;  // refused again next time, and handled then
  aliveRevision_ = revision;
  server::logEvent(server::LogLevel::kWarn, "cluster_presence_lapsed",
                   {{"node", name_}, {"incarnation", number_}});
  for (const auto& doc : liveDocuments()) {
    if (!doc->ownedHere() && !doc->owner().empty())
      doc->rehome("this node's presence in the cluster lapsed, and the owner may have dropped its sessions");
  }
}

void ClusterNode::heartbeat() {
  renewPresence();
  std::set<std::pair<std::string, uint64_t>> nodes;  // (name, incarnation) of other nodes' sessions here
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [session, who] : remoteSubscribers_)
      nodes.emplace(who->node(), sessionIncarnation(session));
  }
  for (const auto& [node, incarnation] : nodes) {
    kvEntry* raw = nullptr;
    const natsStatus s = kvStore_Get(&raw, alive_.get(), node.c_str());
    KvEntryPtr entry(raw);
    if (s != NATS_OK && s != NATS_NOT_FOUND) continue;  // NATS unavailable: decide nothing
    if (s == NATS_OK && std::to_string(incarnation) == kvEntry_ValueString(entry.get())) continue;
    server::logEvent(server::LogLevel::kInfo, "cluster_node_gone",
                     {{"node", name_}, {"gone", node}, {"incarnation", incarnation}});
    // Their subscribers go with the next prunes (pruneRemoteSubscribers).
    for (const auto& doc : liveDocuments()) doc->dropRemoteSessions(node, incarnation);
  }
}

void ClusterNode::pruneRemoteSubscribers() {
  std::set<uint64_t> joined;
  for (const auto& doc : liveDocuments()) {
    for (uint64_t session : doc->remoteSessionIds()) joined.insert(session);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  // Two passes apart: a session that is joining right now has its
  // subscriber (remoteSubscriber) a moment before a document records it.
  std::set<uint64_t> unjoined;
  for (auto it = remoteSubscribers_.begin(); it != remoteSubscribers_.end();) {
    if (joined.count(it->first) != 0) {
      ++it;
    } else if (unjoinedBefore_.count(it->first) != 0) {
      it = remoteSubscribers_.erase(it);
    } else {
      unjoined.insert(it->first);
      ++it;
    }
  }
  unjoinedBefore_ = std::move(unjoined);
  stats_.remoteSessions = static_cast<int64_t>(remoteSubscribers_.size());
}

void ClusterNode::monitor() {
  const auto period = std::chrono::milliseconds(std::max<int64_t>(config_.leaseMs / 3, 50));
  while (true) {
    {
      std::unique_lock<std::mutex> lock(monitorMutex_);
      monitorWake_.wait_for(lock, period, [this] { return stopping_ || reconnected_.load(); });
      if (stopping_) return;
    }
    if (reconnected_.exchange(false)) {
      server::logEvent(server::LogLevel::kInfo, "cluster_reconnected", {{"node", name_}});
      for (const auto& doc : liveDocuments()) doc->askOutcomes();
    }
    heartbeat();
    pruneRemoteSubscribers();
    for (const auto& doc : liveDocuments()) {
      if (doc->ownedHere()) {
        const Status renewed = leases_->renew(doc->id());
        if (renewed.code() == ErrorCode::kNotFound) {
          doc->rehome("this node's lease was lost: " + renewed.message());
        } else if (renewed.isOk() && doc->journalFailed()) {
          // Another node wrote to the journal, or NATS was down and is back:
          // JetStream decides what the document holds, so load it again.
          // While NATS stays down the host keeps serving what it has
          // (reads go on, writes are refused by the journal).
          doc->rehome("its journal refused a write; reloading the document from JetStream");
        }
        continue;
      }
      if (doc->notOwnerReported()) {
        doc->rehome("the owner did not know it");
        continue;
      }
      if (doc->owner().empty()) {
        // No node could load it last time (NATS without quorum, a damaged
        // journal): try again; its sessions hear only of a success.
        doc->rehome("no node could load it before");
        continue;
      }
      auto owner = leases_->ownerOf(doc->id());
      if (!owner.isOk()) continue;  // NATS unavailable: keep what is known
      const std::string now = owner->value_or("");
      if (now != doc->owner()) {
        doc->rehome(now.empty() ? "the owner's lease expired" : "the lease moved to " + now);
      } else {
        // An answer lost in NATS (a server that died with it in flight, on
        // the owner's side, where this node sees no reconnection) is asked
        // for again once it is overdue.
        doc->askOverdue(std::chrono::steady_clock::now() - 2 * std::chrono::milliseconds(config_.leaseMs));
      }
    }
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = localSessions_.begin(); it != localSessions_.end();) {
      if (it->second.expired()) {
        outstanding_.erase(it->first);
        it = localSessions_.erase(it);
      } else {
        ++it;
      }
    }
  }
}

}  // namespace tessera::cluster
