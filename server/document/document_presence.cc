// Presence of a document (docs/PROTOCOL.md §6.3): who has it open and what they
// selected, sent as changes coalesced per 100 ms, the whole list to joiners
// and to participants whose queue dropped presence (PROTOCOL 6.3). Part of
// DocumentHost: every function runs in the host's serial queue.
#include <boost/asio/post.hpp>

#include "server/document/document_host.h"
#include "server/document/replies.h"

namespace tessera::server {

void DocumentHost::join(std::shared_ptr<Subscriber> who, std::string name, wire::Role role) {
  queue_.post(Lane::kInteractive, [self = shared_from_this(), who, name = std::move(name), role] {
    const uint64_t session = who->sessionId();
    self->participants_[session] = {who, name, role, {}};
    self->presence_.changed.insert(session);
    self->presence_.left.erase(session);
    self->presence_.needFull.insert(session);
    self->presenceChanged();
  });
}

void DocumentHost::leave(uint64_t session) {
  queue_.post(Lane::kInteractive, [self = shared_from_this(), session] {
    self->participants_.erase(session);
    self->commits_.stopRecording(session);
    for (auto& [key, view] : self->views_) view.subscribers.erase(session), view.knownVersion.erase(session);
    self->dropUnwatchedViews();
    self->presence_.changed.erase(session);
    self->presence_.needFull.erase(session);
    self->presence_.left.insert(session);
    self->presenceChanged();
  });
}

void DocumentHost::select(std::shared_ptr<Subscriber> who, uint64_t clientSeq, wire::Selection selection) {
  queue_.post(
      Lane::kInteractive, [self = shared_from_this(), who, clientSeq, selection = std::move(selection)] {
        auto it = self->participants_.find(who->sessionId());
        if (it == self->participants_.end()) return;
        // Every participant receives every selection: only real, bounded ones.
        Status valid = Status::ok();
        const int count = selection.vertex_ids_size() + selection.edge_ids_size() + selection.face_ids_size();
        if (count > self->config_.limits.selectionMaxIds) {
          valid = invalidArgument("select: " + std::to_string(count) + " ids, above the limit of " +
                                  std::to_string(self->config_.limits.selectionMaxIds));
        }
        for (uint64_t id : selection.vertex_ids()) {
          if (valid.isOk()) valid = self->counts_.check(VertexId::fromPacked(id));
        }
        for (uint64_t id : selection.edge_ids()) {
          if (valid.isOk()) valid = self->counts_.check(EdgeId::fromPacked(id));
        }
        for (uint64_t id : selection.face_ids()) {
          if (valid.isOk()) valid = self->counts_.check(FaceId::fromPacked(id));
        }
        if (!valid.isOk()) {
          who->send({frameOf(rejectFor(clientSeq, valid.withContext("selection of document " +
                                                                    std::to_string(self->id_.value))),
                             self->config_.limits.maxFrameBytes),
                     nullptr});
          return;
        }
        it->second.selection = selection;
        self->presence_.changed.insert(who->sessionId());
        self->presenceChanged();
      });
}

void DocumentHost::resendPresence(uint64_t session) {
  queue_.post(Lane::kInteractive, [self = shared_from_this(), session] {
    if (!self->participants_.count(session)) return;
    self->presence_.needFull.insert(session);
    self->presenceChanged();
  });
}

// Changes within 100 ms share one broadcast, and a broadcast carries only
// what changed (who joined, left or selected), so its size follows the
// changes, not the participants times their selections; joiners and
// participants whose queue dropped presence get the whole list instead.
void DocumentHost::presenceChanged() {
  if (presencePending_) return;
  presencePending_ = true;
  presenceTimer_.expires_after(std::chrono::milliseconds(100));
  presenceTimer_.async_wait([self = shared_from_this()](const boost::system::error_code&) {
    self->queue_.post(Lane::kInteractive, [self] {
      self->presencePending_ = false;
      self->broadcastPresence();
    });
  });
}

void DocumentHost::broadcastPresence() {
  PresenceChanges changes = std::exchange(presence_, {});
  auto participantMessage = [&](bool full) {
    wire::ServerMessage m;
    wire::Presence* p = m.mutable_presence();
    p->set_document_id(id_.value);
    p->set_full(full);
    for (const auto& [session, participant] : participants_) {
      if (!full && !changes.changed.count(session)) continue;
      wire::Participant* out = p->add_participants();
      out->set_session_id(session);
      out->set_name(participant.name);
      out->set_role(participant.role);
      *out->mutable_selection() = participant.selection;
    }
    if (!full) {
      for (uint64_t session : changes.left) p->add_left_session_ids(session);
    }
    return frameOf(m, config_.limits.maxFrameBytes);
  };
  std::shared_ptr<const std::string> changeFrame, fullFrame;
  if (!changes.changed.empty() || !changes.left.empty()) changeFrame = participantMessage(false);
  if (!changes.needFull.empty()) fullFrame = participantMessage(true);
  for (const auto& [session, participant] : participants_) {
    const bool full = changes.needFull.count(session) > 0;
    const auto& frame = full ? fullFrame : changeFrame;
    if (!frame) continue;
    if (auto who = participant.who.lock()) {
      who->send(
          {.frame = frame, .delta = nullptr, .snapshotOf = 0, .presenceOf = id_.value, .presenceFull = full});
    }
  }
}

}  // namespace tessera::server
