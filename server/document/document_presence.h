// Presence of a document (docs/PROTOCOL.md §6.3): who has it open, in which
// role, and what they selected. A broadcast carries only what changed since
// the last (who joined, left or selected), so its size follows the changes,
// not the participants times their selections; joiners and participants
// whose queue dropped presence get the whole list instead. Its host calls it
// on its strand and chooses when to broadcast (it coalesces the changes of
// 100 ms into one broadcast); nothing here waits or posts.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "core/hierarchy/ids.h"
#include "core/util/status.h"
#include "protocol/tessera.pb.h"
#include "server/base/config.h"
#include "server/document/subscriber.h"

namespace tessera::server {

class DocumentPresence {
 public:
  DocumentPresence(uint64_t documentId, uint32_t maxFrameBytes)
      : documentId_(documentId), maxFrameBytes_(maxFrameBytes) {}

  // A participant joins (or joins again) with no selection; it gets the
  // whole list at the next broadcast, the others hear of it.
  void join(std::shared_ptr<Subscriber> who, std::string name, wire::Role role);
  // The others hear that it left.
  void leave(uint64_t session);
  bool isParticipant(uint64_t session) const { return participants_.count(session) > 0; }
  // A participant's selection (checkSelection first); the others hear of it.
  // Ignored for a session that is no participant.
  void select(uint64_t session, wire::Selection selection);
  // The participant gets the whole list at the next broadcast (its queue
  // dropped presence); false, and nothing changes, for a session that is no
  // participant.
  bool resendTo(uint64_t session);

  // Sends what changed since the last broadcast: the changes to those that
  // hold the list, the whole list to those that need it.
  void broadcast();
  // Sends `frame` to every participant (a document-wide error).
  void sendToAll(const std::shared_ptr<const std::string>& frame) const;

 private:
  struct Participant {
    std::weak_ptr<Subscriber> who;
    std::string name;
    wire::Role role;
    wire::Selection selection;
  };
  // Whose presence others have not heard of yet, and who needs the whole list.
  struct Changes {
    std::set<uint64_t> changed, left, needFull;
  };
  std::shared_ptr<const std::string> presenceFrame(const Changes& changes, bool full) const;

  const uint64_t documentId_;
  const uint32_t maxFrameBytes_;
  std::map<uint64_t, Participant> participants_;  // by session
  Changes changes_;
};

// Every participant receives every selection: only real, bounded ones. Ok
// for at most --selection-max-ids ids that each exist in the document (its
// level counts); else the error names the first that does not.
Status checkSelection(const wire::Selection& selection, const LevelCounts& counts, const Limits& limits);

}  // namespace tessera::server
