#include "server/document/outcome_book.h"

#include <string>

#include "server/document/replies.h"

namespace tessera::server {

void OutcomeBook::setLoaded(std::map<Key, CommandOutcome> outcomes, uint64_t fromVersion) {
  loaded_ = std::move(outcomes);
  loadedFrom_ = fromVersion;
}

void OutcomeBook::remember(Key key, CommandOutcome outcome) {
  recent_[key] = std::move(outcome);
  recentOrder_.push_back(key);
  if (recentOrder_.size() > kRecent) {
    recent_.erase(recentOrder_.front());
    recentOrder_.pop_front();
  }
}

const CommandOutcome* OutcomeBook::find(Key key) const {
  if (auto a = loaded_.find(key); a != loaded_.end()) return &a->second;
  if (auto b = recent_.find(key); b != recent_.end()) return &b->second;
  return nullptr;
}

wire::ServerMessage OutcomeBook::answer(store::DocumentId document, uint64_t clientSeq,
                                        const CommandOutcome* found) const {
  if (found != nullptr) {
    // Applied and durable before the move: the Ack it never got.
    wire::ServerMessage m = ackFor(clientSeq, document.value);
    wire::Ack* ack = m.mutable_ack();
    ack->set_version(found->version);
    if (!found->editIds.empty()) ack->set_edit_id(found->editIds.back());
    if (found->editIds.size() > 1) {
      for (uint64_t e : found->editIds) ack->add_edit_ids(e);
    }
    return m;
  }
  // Neither in the journal as loaded (fenced when this node took the
  // document: nothing written after can come from an old owner) nor
  // applied here since.
  return rejectFor(
      clientSeq,
      Status(ErrorCode::kNotFound,
             "command " + std::to_string(clientSeq) + " was not applied: document " +
                 std::to_string(document.value) + "'s journal holds no entry from it (since version " +
                 std::to_string(loadedFrom_) +
                 "); it was lost with its owner node or on the way to it; send it again"));
}

}  // namespace tessera::server
