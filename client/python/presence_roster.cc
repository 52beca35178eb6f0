#include "client/python/presence_roster.h"

namespace tessera::python {

void PresenceRoster::apply(const wire::ServerMessage& message) {
  if (!message.has_presence()) return;
  const wire::Presence& p = message.presence();
  auto& held = documents_[p.document_id()];
  if (p.full()) held.clear();
  for (const wire::Participant& participant : p.participants()) held[participant.session_id()] = participant;
  for (uint64_t left : p.left_session_ids()) held.erase(left);
}

std::vector<wire::Participant> PresenceRoster::participants(uint64_t document) const {
  std::vector<wire::Participant> out;
  const auto held = documents_.find(document);
  if (held == documents_.end()) return out;
  for (const auto& [id, participant] : held->second) out.push_back(participant);
  return out;
}

}  // namespace tessera::python
