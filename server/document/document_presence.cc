#include "server/document/document_presence.h"

#include <utility>

#include "server/document/replies.h"

namespace tessera::server {

void DocumentPresence::join(std::shared_ptr<Subscriber> who, std::string name, wire::Role role) {
  const uint64_t session = who->sessionId();
  participants_[session] = {who, std::move(name), role, {}};
  changes_.changed.insert(session);
  changes_.left.erase(session);
  changes_.needFull.insert(session);
}

void DocumentPresence::leave(uint64_t session) {
  participants_.erase(session);
  changes_.changed.erase(session);
  changes_.needFull.erase(session);
  changes_.left.insert(session);
}

void DocumentPresence::select(uint64_t session, wire::Selection selection) {
  auto it = participants_.find(session);
  if (it == participants_.end()) return;
  it->second.selection = std::move(selection);
  changes_.changed.insert(session);
}

bool DocumentPresence::resendTo(uint64_t session) {
  if (!participants_.count(session)) return false;
  changes_.needFull.insert(session);
  return true;
}

std::shared_ptr<const std::string> DocumentPresence::presenceFrame(const Changes& changes, bool full) const {
  wire::ServerMessage m;
  wire::Presence* p = m.mutable_presence();
  p->set_document_id(documentId_);
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
  return frameOf(m, maxFrameBytes_);
}

void DocumentPresence::broadcast() {
  Changes changes = std::exchange(changes_, {});
  std::shared_ptr<const std::string> changeFrame, fullFrame;
  if (!changes.changed.empty() || !changes.left.empty()) changeFrame = presenceFrame(changes, false);
  if (!changes.needFull.empty()) fullFrame = presenceFrame(changes, true);
  for (const auto& [session, participant] : participants_) {
    const bool full = changes.needFull.count(session) > 0;
    const auto& frame = full ? fullFrame : changeFrame;
    if (!frame) continue;
    if (auto who = participant.who.lock()) {
      who->send({.frame = frame,
                 .delta = nullptr,
                 .snapshotOf = 0,
                 .presenceOf = documentId_,
                 .presenceFull = full});
    }
  }
}

void DocumentPresence::sendToAll(const std::shared_ptr<const std::string>& frame) const {
  for (const auto& [session, participant] : participants_) {
    if (auto who = participant.who.lock()) who->send({frame, nullptr});
  }
}

Status checkSelection(const wire::Selection& selection, const LevelCounts& counts, const Limits& limits) {
  Status valid = Status::ok();
  const int count = selection.vertex_ids_size() + selection.edge_ids_size() + selection.face_ids_size();
  if (count > limits.selectionMaxIds) {
    valid = invalidArgument("select: " + std::to_string(count) + " ids, above the limit of " +
                            std::to_string(limits.selectionMaxIds));
  }
  for (uint64_t id : selection.vertex_ids()) {
    if (valid.isOk()) valid = counts.check(VertexId::fromPacked(id));
  }
  for (uint64_t id : selection.edge_ids()) {
    if (valid.isOk()) valid = counts.check(EdgeId::fromPacked(id));
  }
  for (uint64_t id : selection.face_ids()) {
    if (valid.isOk()) valid = counts.check(FaceId::fromPacked(id));
  }
  return valid;
}

}  // namespace tessera::server
