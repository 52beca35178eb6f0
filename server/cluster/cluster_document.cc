#include "server/cluster/cluster_document.h"

#include <set>
#include <utility>

#include "server/base/log.h"
#include "server/document/replies.h"

namespace tessera::cluster {

ClusterDocument::~ClusterDocument() {
  if (host_) {
    host_.reset();
    --node_.stats().documentsOwned;
    node_.registry().forget(id_);
    node_.leases().release(id_);
    server::logEvent(server::LogLevel::kInfo, "lease_released", {{"doc", id_.value}, {"node", node_.name()}});
  }
}

Status ClusterDocument::resolve() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (host_ || !owner_.empty()) return Status::ok();  // resolved already (another opener, or the monitor)
  const Status resolved = resolveLocked();
  whyUnowned_ = resolved.isOk() ? std::string() : resolved.message();
  if (resolved.isOk()) whyLost_.clear();
  return resolved;
}

bool ClusterDocument::ownerExpectedSoon() {
  std::lock_guard<std::mutex> lock(mutex_);
  return !host_ && owner_.empty() && ownLeaseStale_;
}

Status ClusterDocument::resolveLocked() {
  std::string owner;
  TESSERA_ASSIGN_OR_RETURN(bool mine, node_.leases().acquire(id_, &owner, &ownLeaseStale_));
  if (!mine) {
    owner_ = owner;
    return Status::ok();
  }
  // Read afresh from the store: the registry may still hold a host from
  // before this node last lost the document.
  node_.registry().forget(id_);
  auto host = node_.registry().open(id_);
  if (!host.isOk()) {
    node_.leases().release(id_);
    return host.status();
  }
  // Fenced: from here on, an old owner that loaded the journal before
  // cannot append, so the loaded journal is the whole truth of what was
  // applied (and answerOutcomes can say "not applied").
  const Status fenced = node_.store().fenceJournal(id_);
  if (!fenced.isOk()) {
    node_.registry().forget(id_);
    node_.leases().release(id_);
    return fenced;
  }
  host_ = std::move(*host);
  // Commands whose journal write's outcome is unknown (NATS timed out)
  // come here, however late, to be answered by whoever owns it next.
  host_->onUndecided([weak = weak_from_this()](server::DocumentHost::Undecided undecided) {
    if (auto self = weak.lock()) self->undecidedArrived(std::move(undecided));
  });
  ++node_.stats().documentsOwned;
  owner_ = node_.name();
  server::logEvent(server::LogLevel::kInfo, "lease_taken", {{"doc", id_.value}, {"node", node_.name()}});
  return Status::ok();
}

void ClusterDocument::forward(uint64_t session, Forward::Kind kind,
                              const std::function<void(Forward&)>& fill) {
  if (owner_.empty()) return;  // no owner known: rehome() will join the session when one is
  Forward request;
  request.set_via_node(node_.name());
  request.set_session_id(session);
  request.set_document_id(id_.value);
  request.set_kind(kind);
  if (fill) fill(request);
  node_.forward(owner_, request);
}

void ClusterDocument::join(std::shared_ptr<server::Subscriber> who, std::string name, wire::Role role) {
  std::lock_guard<std::mutex> lock(mutex_);
  const uint64_t session = who->sessionId();
  sessions_[session] = LocalSession{who, name, role, std::nullopt};
  node_.addLocalSession(session, who);
  if (host_) return host_->join(std::move(who), std::move(name), role);
  forward(session, Forward::KIND_JOIN, [&](Forward& f) {
    f.set_name(name);
    f.set_role(role);
  });
}

void ClusterDocument::leave(uint64_t session) {
  std::lock_guard<std::mutex> lock(mutex_);
  sessions_.erase(session);
  if (host_) return host_->leave(session);
  forward(session, Forward::KIND_LEAVE, nullptr);
}

void ClusterDocument::select(std::shared_ptr<server::Subscriber> who, uint64_t clientSeq,
                             wire::Selection selection) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (host_) return host_->select(std::move(who), clientSeq, std::move(selection));
  forward(who->sessionId(), Forward::KIND_SELECT, [&](Forward& f) {
    f.mutable_message()->set_client_seq(clientSeq);
    *f.mutable_message()->mutable_select()->mutable_selection() = std::move(selection);
  });
}

void ClusterDocument::resendPresence(uint64_t session) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (host_) return host_->resendPresence(session);
  forward(session, Forward::KIND_RESEND_PRESENCE, nullptr);
}

void ClusterDocument::subscribe(std::shared_ptr<server::Subscriber> who, const wire::Subscribe& request,
                                uint64_t clientSeq, bool resync) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = sessions_.find(who->sessionId()); it != sessions_.end()) {
    it->second.subscription = request;
    // Nobody to answer it now: the owner found next does (rejoinLocked).
    if (!host_ && owner_.empty() && !resync) it->second.unansweredSubscribe = clientSeq;
  }
  if (host_) return host_->subscribe(std::move(who), request, clientSeq, resync);
  forward(who->sessionId(), Forward::KIND_SUBSCRIBE, [&](Forward& f) {
    f.mutable_message()->set_client_seq(clientSeq);
    *f.mutable_message()->mutable_subscribe() = request;
    f.set_resync(resync);
  });
}

void ClusterDocument::setView(std::shared_ptr<server::Subscriber> who, uint64_t clientSeq, wire::View view) {
  std::lock_guard<std::mutex> lock(mutex_);
  // A session that moves to another owner resubscribes with its latest view.
  if (auto it = sessions_.find(who->sessionId());
      it != sessions_.end() && it->second.subscription && it->second.subscription->has_view()) {
    *it->second.subscription->mutable_view() = view;
  }
  if (host_) return host_->setView(std::move(who), clientSeq, std::move(view));
  forward(who->sessionId(), Forward::KIND_SET_VIEW, [&](Forward& f) {
    f.mutable_message()->set_client_seq(clientSeq);
    *f.mutable_message()->mutable_set_view()->mutable_view() = std::move(view);
  });
}

void ClusterDocument::unsubscribe(uint64_t session) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = sessions_.find(session); it != sessions_.end()) it->second.subscription.reset();
  if (host_) return host_->unsubscribe(session);
  forward(session, Forward::KIND_UNSUBSCRIBE, nullptr);
}

void ClusterDocument::command(std::shared_ptr<server::Subscriber> author, std::string authorName,
                              wire::ClientMessage message) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (host_) return host_->command(std::move(author), std::move(authorName), std::move(message));
  if (owner_.empty()) {
    // Between owners: refused now rather than lost later.
    // Why, when a load failed (e.g. NATS without quorum), not only that.
    std::string why =
        whyUnowned_.empty() ? "a takeover is under way" : "no node could load it: " + whyUnowned_;
    if (!whyLost_.empty()) why = "its last owner gave it up: " + whyLost_ + "; " + why;
    wire::ServerMessage reject =
        server::rejectFor(message.client_seq(), ioError(toString(id_) + " has no owner node right now (" +
                                                        why + "): the edit was not applied; send it again"));
    author->send({server::frameOf(reject, node_.maxFrameBytes()), nullptr});
    return;
  }
  // Until its Ack or Reject comes back: if the owner dies first, the new
  // owner is asked what became of it (rehome).
  node_.noteOutstanding(author->sessionId(), message.client_seq(), id_);
  forward(author->sessionId(), Forward::KIND_COMMAND, [&](Forward& f) {
    f.set_name(authorName);
    *f.mutable_message() = std::move(message);
  });
}

void ClusterDocument::exportGlb(std::shared_ptr<server::Subscriber> who, uint64_t clientSeq,
                                wire::ExportDocument request) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (host_) return host_->exportGlb(std::move(who), clientSeq, std::move(request));
  forward(who->sessionId(), Forward::KIND_EXPORT, [&](Forward& f) {
    f.mutable_message()->set_client_seq(clientSeq);
    *f.mutable_message()->mutable_export_document() = std::move(request);
  });
}

void ClusterDocument::morphControl(std::shared_ptr<server::Subscriber> who, uint64_t clientSeq,
                                   wire::GetMorphControl request) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (host_) return host_->morphControl(std::move(who), clientSeq, std::move(request));
  forward(who->sessionId(), Forward::KIND_MORPH_CONTROL, [&](Forward& f) {
    f.mutable_message()->set_client_seq(clientSeq);
    *f.mutable_message()->mutable_get_morph_control() = std::move(request);
  });
}

void ClusterDocument::cage(std::shared_ptr<server::Subscriber> who, uint64_t clientSeq,
                           wire::GetCage request) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (host_) return host_->cage(std::move(who), clientSeq, std::move(request));
  forward(who->sessionId(), Forward::KIND_CAGE, [&](Forward& f) {
    f.mutable_message()->set_client_seq(clientSeq);
    *f.mutable_message()->mutable_get_cage() = std::move(request);
  });
}

bool ClusterDocument::serveRemote(const Forward& request) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!host_) return false;
  const uint64_t session = request.session_id();
  const wire::ClientMessage& m = request.message();
  using F = Forward;
  auto who = node_.remoteSubscriber(request.via_node(), session);
  switch (request.kind()) {
    case F::KIND_JOIN:
      if (remoteSessions_.emplace(session, request.via_node()).second && remoteSessions_.size() == 1) {
        lock.unlock();  // pin() takes the node's lock, which the monitor holds before ours
        node_.pin(shared_from_this());
        lock.lock();
        if (!host_) return false;
      }
      host_->join(who, request.name(), request.role());
      break;
    case F::KIND_LEAVE:
      host_->leave(session);
      if (remoteSessions_.erase(session) && remoteSessions_.empty()) {
        lock.unlock();
        node_.unpin(id_);  // may destroy this document when no local session holds it
        return true;
      }
      break;
    case F::KIND_SELECT:
      host_->select(who, m.client_seq(), m.select().selection());
      break;
    case F::KIND_RESEND_PRESENCE:
      host_->resendPresence(session);
      break;
    case F::KIND_SUBSCRIBE:
      host_->subscribe(who, m.subscribe(), m.client_seq(), request.resync());
      break;
    case F::KIND_SET_VIEW:
      host_->setView(who, m.client_seq(), m.set_view().view());
      break;
    case F::KIND_UNSUBSCRIBE:
      host_->unsubscribe(session);
      break;
    case F::KIND_COMMAND:
      host_->command(who, request.name(), m);
      break;
    case F::KIND_EXPORT:
      host_->exportGlb(who, m.client_seq(), m.export_document());
      break;
    case F::KIND_MORPH_CONTROL:
      host_->morphControl(who, m.client_seq(), m.get_morph_control());
      break;
    case F::KIND_CAGE:
      host_->cage(who, m.client_seq(), m.get_cage());
      break;
    case F::KIND_OUTCOMES:
      host_->answerOutcomes(
          who, std::vector<uint64_t>(request.client_seqs().begin(), request.client_seqs().end()));
      break;
    default:
      break;  // refused by the node before it came here
  }
  return true;
}

bool ClusterDocument::ownedHere() {
  std::lock_guard<std::mutex> lock(mutex_);
  return host_ != nullptr;
}

std::string ClusterDocument::owner() {
  std::lock_guard<std::mutex> lock(mutex_);
  return owner_;
}

bool ClusterDocument::journalFailed() {
  std::lock_guard<std::mutex> lock(mutex_);
  return host_ && host_->journalFailed();
}

void ClusterDocument::undecidedArrived(server::DocumentHost::Undecided undecided) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& [weak, seq] : undecided) {
    auto who = weak.lock();
    // Other nodes' sessions: their nodes still wait for an answer, and ask.
    if (who && !dynamic_cast<RemoteSubscriber*>(who.get())) node_.noteOutstanding(who->sessionId(), seq, id_);
  }
  answerBookLocked();
}

void ClusterDocument::answerBookLocked() {
  // Kept while the host here is the one that failed (the monitor reloads
  // it) or no owner is known (a reload may fail while NATS recovers): the
  // next rehome answers them.
  if (host_ ? host_->journalFailed() : owner_.empty()) return;
  for (auto& [who, seqs] : node_.outstandingOf(id_, /*take=*/host_ != nullptr)) {
    if (host_) {
      host_->answerOutcomes(who, std::move(seqs));
    } else {
      askOwnerLocked(who->sessionId(), seqs);
    }
  }
}

void ClusterDocument::askOwnerLocked(uint64_t session, const std::vector<uint64_t>& seqs) {
  // They stay in the node's book until the owner answers: if the question
  // or its answer is lost (the owner moves, NATS drops it), the next move
  // or reconnection asks again (rehome, askOutcomes).
  forward(session, Forward::KIND_OUTCOMES, [&](Forward& f) {
    for (uint64_t seq : seqs) f.add_client_seqs(seq);
  });
}

void ClusterDocument::askOutcomes() {
  std::lock_guard<std::mutex> lock(mutex_);
  answerBookLocked();
}

void ClusterDocument::askOverdue(std::chrono::steady_clock::time_point before) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (host_ || owner_.empty()) return;  // here, or between owners: the next rehome answers them
  // The owner answers each from its journal, or not at all while it is
  // still waiting for the command's journal write (its Ack follows).
  for (auto& [who, seqs] : node_.outstandingOf(id_, /*take=*/false, before))
    askOwnerLocked(who->sessionId(), seqs);
}

bool ClusterDocument::hasRemoteSessions() {
  std::lock_guard<std::mutex> lock(mutex_);
  return !remoteSessions_.empty();
}

std::vector<uint64_t> ClusterDocument::remoteSessionIds() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<uint64_t> ids;
  for (const auto& entry : remoteSessions_) ids.push_back(entry.first);
  return ids;
}

void ClusterDocument::dropRemoteSessions(const std::string& node, uint64_t incarnation) {
  std::unique_lock<std::mutex> lock(mutex_);
  bool dropped = false;
  for (auto it = remoteSessions_.begin(); it != remoteSessions_.end();) {
    if (it->second == node && sessionIncarnation(it->first) == incarnation) {
      if (host_) host_->leave(it->first);
      it = remoteSessions_.erase(it);
      dropped = true;
    } else {
      ++it;
    }
  }
  const bool empty = remoteSessions_.empty();
  const std::string owner = owner_;
  lock.unlock();
  if (!dropped) return;
  // Told, in case it is not dead after all (its heartbeat came late): it
  // then moves its sessions here again, with a resync, instead of its
  // viewers waiting for deltas that no longer come.
  node_.tellNotOwner(node, id_, owner);
  if (empty) node_.unpin(id_);
}

void ClusterDocument::dropHostLocked() {
  if (!host_) return;
  for (const auto& [session, s] : sessions_) host_->leave(session);
  for (const auto& [session, node] : remoteSessions_) host_->leave(session);
  host_.reset();
  --node_.stats().documentsOwned;
  node_.registry().forget(id_);
  node_.leases().release(id_);
}

void ClusterDocument::rehome(const std::string& why) {
  std::unique_lock<std::mutex> lock(mutex_);
  notOwner_ = false;
  const std::string from = owner_;
  const bool hadRemote = !remoteSessions_.empty();
  const std::set<std::string> remoteNodes = leaveOwnerLocked();
  const Status resolved = resolveLocked();
  whyUnowned_ = resolved.isOk() ? std::string() : resolved.message();
  // Kept over the retries that follow: the first cause (e.g. a lease that
  // expired while NATS had no quorum) is what the refused edits must name.
  if (resolved.isOk()) {
    whyLost_.clear();
  } else if (!from.empty()) {
    whyLost_ = why;
  }
  if (from.empty() && !resolved.isOk()) return;  // still no owner: nothing moved, nothing to log
  ++node_.stats().documentsMoved;
  server::logEvent(resolved.isOk() ? server::LogLevel::kInfo : server::LogLevel::kWarn, "document_moved",
                   {{"doc", id_.value},
                    {"node", node_.name()},
                    {"from", from},
                    {"to", owner_},
                    {"reason", why},
                    {"sessions", static_cast<uint64_t>(sessions_.size())},
                    {"error", resolved.isOk() ? std::string() : resolved.message()}});
  // Told before the resync: an edit sent to the old owner and not
  // acknowledged may be lost (docs/CLUSTER.md, "What a client sees"). A
  // retry that fails again (no owner before, none now) tells nobody anew.
  const bool tell = !from.empty() || resolved.isOk();
  const server::Outgoing notice{movedNotice(from, why, resolved), nullptr};
  for (auto& [session, s] : sessions_) {
    auto who = s.who.lock();
    if (!who) continue;
    if (tell) who->send(notice);
    if (!owner_.empty())
      rejoinLocked(session, who, s);  // otherwise when an owner is found (the monitor tries again)
  }
  // The unanswered commands of this node's sessions (forwarded to the old
  // owner, or undecided by the failed host here): the owner, here or
  // elsewhere, answers from the journal. Other nodes' sessions are moved
  // by their nodes (told below), which ask about their own.
  answerBookLocked();
  lock.unlock();
  // Other nodes' sessions were on the dropped host; even if this node took
  // the document again, their nodes must rejoin them (and ask about their
  // unanswered commands): a NotOwner makes them move.
  for (const std::string& node : remoteNodes) node_.tellNotOwner(node, id_, owner_);
  if (hadRemote) node_.unpin(id_);
}

std::set<std::string> ClusterDocument::leaveOwnerLocked() {
  std::set<std::string> remoteNodes;
  if (host_) {
    // The failed host's commands whose journal write may or may not be
    // stored are in the node's book (undecidedArrived): answered once the
    // journal is loaded again.
    for (const auto& entry : remoteSessions_) remoteNodes.insert(entry.second);
    dropHostLocked();
    // Other nodes' sessions go with the host; their nodes see the lease
    // change and move them.
    remoteSessions_.clear();
  } else {
    for (const auto& entry : sessions_) forward(entry.first, Forward::KIND_LEAVE, nullptr);
  }
  owner_.clear();
  return remoteNodes;
}

std::shared_ptr<const std::string> ClusterDocument::movedNotice(const std::string& from,
                                                                const std::string& why,
                                                                const Status& resolved) {
  wire::ServerMessage notice;
  notice.mutable_error()->set_code(wire::ERROR_CODE_INTERNAL);
  const std::string to = owner_.empty() ? "none yet (" + resolved.message() + ")" : "node " + owner_;
  notice.mutable_error()->set_message(
      toString(id_) + " moved from node " + (from.empty() ? "?" : from) + " to " + to + " (" + why +
      "): an edit without its Ack may be lost; " +
      (owner_.empty() ? "edits are refused until a node can load it" : "a resync snapshot follows"));
  return server::frameOf(notice, node_.maxFrameBytes());
}

void ClusterDocument::rejoinLocked(uint64_t session, const std::shared_ptr<server::Subscriber>& who,
                                   LocalSession& s) {
  // Its unanswered commands are asked after every session moved (rehome).
  // A Subscribe nobody answered yet is answered now, as a first one (an
  // Ack, then the snapshot); the others resync.
  const uint64_t seq = std::exchange(s.unansweredSubscribe, 0);
  const bool resync = seq == 0;
  if (host_) {
    host_->join(who, s.name, s.role);
    if (s.subscription) host_->subscribe(who, *s.subscription, seq, resync);
    return;
  }
  forward(session, Forward::KIND_JOIN, [&](Forward& f) {
    f.set_name(s.name);
    f.set_role(s.role);
  });
  if (s.subscription) {
    forward(session, Forward::KIND_SUBSCRIBE, [&](Forward& f) {
      f.mutable_message()->set_client_seq(seq);
      *f.mutable_message()->mutable_subscribe() = *s.subscription;
      f.set_resync(resync);
    });
  }
}

}  // namespace tessera::cluster
