// What became of the commands a document acknowledged, by the session and
// client_seq that sent them: the journal's entries as loaded (in a cluster
// they name the command they came from) and the last commands acknowledged
// here. A session whose answers may have been lost (its document moved, or
// its node lost frames in a NATS reconnect) asks, and gets the Ack it
// missed or a Reject saying the journal holds no entry from the command
// (docs/CLUSTER.md, "Failover").
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <utility>
#include <vector>

#include "protocol/tessera.pb.h"
#include "server/store/store.h"

namespace tessera::server {

struct CommandOutcome {
  uint64_t version = 0;
  std::vector<uint64_t> editIds;
};

class OutcomeBook {
 public:
  using Key = std::pair<uint64_t, uint64_t>;  // (session, client_seq)

  // The outcomes of the journal's entries after `fromVersion` (the load's
  // snapshot), replacing any loaded before.
  void setLoaded(std::map<Key, CommandOutcome> outcomes, uint64_t fromVersion);
  // A command acknowledged here. Kept a while, the last kRecent of them: in
  // a cluster the Ack travels over NATS and may be lost in a reconnect.
  void remember(Key key, CommandOutcome outcome);
  // Loaded or acknowledged here lately; null when neither.
  const CommandOutcome* find(Key key) const;
  // The Ack a found command missed, or, with no outcome, the Reject that
  // says the journal holds no entry from it.
  wire::ServerMessage answer(store::DocumentId document, uint64_t clientSeq,
                             const CommandOutcome* found) const;

  static constexpr size_t kRecent = 4096;

 private:
  std::map<Key, CommandOutcome> loaded_;
  uint64_t loadedFrom_ = 0;  // the loaded outcomes cover entries after this version
  std::map<Key, CommandOutcome> recent_;
  std::deque<Key> recentOrder_;  // oldest first
};

}  // namespace tessera::server
