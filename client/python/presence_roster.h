// Who has a document open, as Presence messages tell it (docs/PROTOCOL.md
// §6.3): a full list replaces what is held, a change replaces the
// participants it names and removes those who left.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "protocol/tessera.pb.h"

namespace tessera::python {

class PresenceRoster {
 public:
  // A Presence message; others are ignored.
  void apply(const wire::ServerMessage& message);
  // The participants of `document`, by session id (empty before any presence).
  std::vector<wire::Participant> participants(uint64_t document) const;
  void forget(uint64_t document) { documents_.erase(document); }

 private:
  std::map<uint64_t, std::map<uint64_t, wire::Participant>> documents_;
};

}  // namespace tessera::python
