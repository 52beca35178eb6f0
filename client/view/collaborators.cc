#include "client/view/collaborators.h"

#include <algorithm>

namespace tessera::view {

void Collaborators::apply(const wire::Presence& presence, uint64_t ownSession) {
  if (presence.full()) list_.clear();
  auto erase = [&](uint64_t session) {
    std::erase_if(list_, [&](const Collaborator& c) { return c.sessionId == session; });
  };
  for (uint64_t left : presence.left_session_ids()) erase(left);
  for (const wire::Participant& p : presence.participants()) {
    erase(p.session_id());
    Collaborator c{.sessionId = p.session_id(),
                   .name = p.name(),
                   .role = p.role(),
                   .selectedVertices = {},
                   .self = p.session_id() == ownSession};
    c.selectedVertices.assign(p.selection().vertex_ids().begin(), p.selection().vertex_ids().end());
    list_.push_back(std::move(c));
  }
  std::sort(list_.begin(), list_.end(),
            [](const Collaborator& a, const Collaborator& b) { return a.sessionId < b.sessionId; });
}

}  // namespace tessera::view
