// Collaborators: who has the document open, with their role and selection,
// from the server's Presence messages (docs/PROTOCOL.md 6.3), as
// client/web's Collaborators. A full Presence replaces the list; a
// change-form one replaces the entries it names and removes those in
// left_session_ids. The list is kept in session order, as the server orders
// it.
//
// Not thread-safe: the Connection holds its mutex around every call.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "protocol/tessera.pb.h"

namespace tessera::view {

struct Collaborator {
  uint64_t sessionId = 0;
  std::string name;
  wire::Role role = wire::ROLE_UNSPECIFIED;
  std::vector<uint64_t> selectedVertices;
  bool self = false;  // this viewer's own session
};

class Collaborators {
 public:
  // `ownSession`: this viewer's session id, whose entry is marked self.
  void apply(const wire::Presence& presence, uint64_t ownSession);
  const std::vector<Collaborator>& list() const { return list_; }

 private:
  std::vector<Collaborator> list_;  // by session id
};

}  // namespace tessera::view
