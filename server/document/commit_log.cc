#include "server/document/commit_log.h"

#include "protocol/commands.h"
#include "server/base/latency_histogram.h"
#include "server/document/replies.h"

namespace tessera::server {

using Clock = std::chrono::steady_clock;

CommitLog::CommitLog(store::DocumentId document, uint64_t version, uint32_t maxFrameBytes, ServerStats& stats)
    : document_(document),
      maxFrameBytes_(maxFrameBytes),
      stats_(stats),
      durableVersion_(version),
      ackedVersion_(version) {}

void CommitLog::applied(PendingEdit edit) {
  pending_.push_back(std::move(edit));
}

void CommitLog::durable(uint64_t version) {
  durableVersion_ = std::max(durableVersion_, version);
}

void CommitLog::release(const std::function<void(FlushBatch&)>& send) {
  for (const PendingEdit& p : pending_) {
    if (p.version > durableVersion_) break;
    if (p.version <= ackedVersion_) continue;
    ack(p);
  }
  while (!batches_.empty() && batches_.front().toVersion <= durableVersion_) {
    FlushBatch& b = batches_.front();
    send(b);
    // A recorder gets each command after the delta that carries it.
    while (!pending_.empty() && pending_.front().version <= b.toVersion) {
      notifyRecorders(pending_.front());
      pending_.pop_front();
    }
    batches_.pop_front();
  }
}

void CommitLog::ack(const PendingEdit& p) {
  ackedVersion_ = p.version;
  stats_.commitMicros += microsSince(p.applied);
  stats_.ackLatency.addMicros(microsSince(p.applied));
  if (auto author = p.author.lock()) {
    wire::ServerMessage ack = ackFor(p.clientSeq, document_.value);
    ack.mutable_ack()->set_version(p.version);
    ack.mutable_ack()->set_edit_id(p.editId);
    for (uint64_t id : p.batchEditIds) ack.mutable_ack()->add_edit_ids(id);
    author->send({frameOf(ack, maxFrameBytes_), nullptr});
  }
  // Kept a while: in a cluster the Ack travels over NATS and may be lost in
  // a reconnect; the author's node then asks again (outcomeOf).
  outcomes_.remember({p.authorSession, p.clientSeq},
                     {p.version, p.batchEditIds.empty() ? std::vector<uint64_t>{p.editId} : p.batchEditIds});
}

CommitLog::Undecided CommitLog::failed(const Status& status, bool undecidable) {
  Undecided undecided;
  for (const PendingEdit& p : pending_) {
    if (p.version <= ackedVersion_) continue;  // durable, acked
    if (undecidable) {
      undecided.push_back({p.author, p.clientSeq});
      continue;
    }
    if (auto author = p.author.lock()) {
      // Not acknowledged: lost, or (a store that timed out, e.g. NATS
      // without quorum) possibly durable; the document, once reloaded, says.
      author->send(
          {frameOf(rejectFor(p.clientSeq, internalError("the journal write failed (" + status.message() +
                                                        "): the edit was not acknowledged and may be lost")),
                   maxFrameBytes_),
           nullptr});
    }
  }
  pending_.clear();
  batches_.clear();
  return undecided;
}

void CommitLog::record(uint64_t session, std::weak_ptr<Subscriber> who, uint64_t fromVersion) {
  recorders_.try_emplace(session, Recorder{std::move(who), fromVersion});
}

std::optional<wire::ServerMessage> CommitLog::outcomeOf(OutcomeBook::Key key, bool journalFailed) const {
  for (const PendingEdit& p : pending_) {
    // Applied here and not durable yet: its Ack follows as usual.
    if (p.version > ackedVersion_ && p.authorSession == key.first && p.clientSeq == key.second)
      return std::nullopt;
  }
  const CommandOutcome* found = outcomes_.find(key);
  // A failed write (failed()) took its commands out of pending_, and when
  // the store could not know its outcome the entry may be stored: "not
  // applied" could make the client send the edit twice. The asker asks
  // again after the reload (a move), and the reloaded journal answers.
  if (found == nullptr && journalFailed) return std::nullopt;
  return outcomes_.answer(document_, key.second, found);
}

void CommitLog::notifyRecorders(const PendingEdit& p) {
  if (recorders_.empty()) return;
  wire::ServerMessage m;
  wire::AppliedCommand* a = m.mutable_applied_command();
  a->set_document_id(document_.value);
  a->set_version(p.version);
  a->set_edit_id(p.editId);
  for (uint64_t id : p.batchEditIds) a->add_edit_ids(id);
  a->set_author_session_id(p.authorSession);
  a->set_author_name(p.authorName);
  const auto appliedAt =
      std::chrono::system_clock::now() -
      std::chrono::duration_cast<std::chrono::system_clock::duration>(Clock::now() - p.applied);
  a->set_server_time_unix_ms(static_cast<uint64_t>(
      std::chrono::duration_cast<std::chrono::milliseconds>(appliedAt.time_since_epoch()).count()));
  copyEditCommand(p.command, *a);
  auto frame = frameOf(m, maxFrameBytes_);
  if (!frame) return;
  for (auto it = recorders_.begin(); it != recorders_.end();) {
    auto who = it->second.who.lock();
    if (!who) {
      it = recorders_.erase(it);
      continue;
    }
    if (p.version > it->second.fromVersion) who->send({frame, nullptr});
    ++it;
  }
}

}  // namespace tessera::server
