// The commit stage of a document (docs/ARCHITECTURE.md, "One edit, end to
// end"): what was applied and waits for its journal commit, the deltas that
// wait for the edits they carry (with --deltas-after-durable), the Acks sent
// once durable, the recorders' commands sent after the delta that carries
// them, and the answers to "what became of my command" (docs/CLUSTER.md,
// "Failover"). It runs on its host's strand and sends through the
// subscribers; it applies and encodes nothing.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/util/status.h"
#include "protocol/tessera.pb.h"
#include "server/base/server_stats.h"
#include "server/document/delta.h"
#include "server/document/outcome_book.h"
#include "server/document/subscriber.h"
#include "server/store/store.h"

namespace tessera::server {

// An applied command, waiting for its commit (its Ack) and for the delta
// that carries it (its recorders' AppliedCommand).
struct PendingEdit {
  uint64_t version;
  std::weak_ptr<Subscriber> author;
  uint64_t authorSession, clientSeq, editId;
  std::vector<uint64_t> batchEditIds;  // an EditBatch's, for its Ack
  std::chrono::steady_clock::time_point applied;
  wire::ClientMessage command;  // as the author sent it, for recorders
  std::string authorName;
};

// One flush: the delta of every view up to `toVersion`, by view key.
struct FlushBatch {
  uint64_t toVersion;
  std::map<std::string, std::shared_ptr<const DeltaContent>> deltas;
  std::map<std::string, std::shared_ptr<const std::string>> frames;
};

class CommitLog {
 public:
  // `version`: the document's version as loaded, durable by definition.
  CommitLog(store::DocumentId document, uint64_t version, uint32_t maxFrameBytes, ServerStats& stats);

  // A command applied as `edit.version` (the newest).
  void applied(PendingEdit edit);
  // The newest applied command not yet released, or null.
  const PendingEdit* newest() const { return pending_.empty() ? nullptr : &pending_.back(); }
  // A flush's deltas, held until every edit they carry is durable.
  void flushed(FlushBatch batch) { batches_.push_back(std::move(batch)); }

  // The journal holds every entry up to `version`.
  void durable(uint64_t version);
  // Acks every durable edit, then hands every batch whose edits are all
  // durable to `send` (which skips one already sent at its flush) and, after
  // each, sends its commands to the recorders.
  void release(const std::function<void(FlushBatch&)>& send);

  // Who must be told when a journal write fails and the store cannot know
  // whether it stored the entry (outcomeUnknown): each author and client_seq.
  using Undecided = std::vector<std::pair<std::weak_ptr<Subscriber>, uint64_t>>;
  // A journal write failed: every edit not yet acknowledged is refused
  // (lost), or, when `undecidable`, returned for whoever reloads the
  // document to answer from the journal. Pending edits and batches go.
  Undecided failed(const Status& status, bool undecidable);

  // Nothing applied waits for its commit: a snapshot now holds only what
  // the journal holds.
  bool atRest(uint64_t version) const { return pending_.empty() && version == durableVersion_; }

  // A subscriber that asked with_commands gets the commands after `fromVersion`.
  void record(uint64_t session, std::weak_ptr<Subscriber> who, uint64_t fromVersion);
  void stopRecording(uint64_t session) { recorders_.erase(session); }

  void setLoadedOutcomes(std::map<OutcomeBook::Key, CommandOutcome> outcomes, uint64_t fromVersion) {
    outcomes_.setLoaded(std::move(outcomes), fromVersion);
  }
  // What became of (session, client_seq): its Ack, or a Reject saying the
  // journal holds nothing from it. None while it still waits for its commit
  // (its Ack follows), nor, after a failed journal write (`journalFailed`),
  // for one this host does not know: the entry may be stored, and the
  // document once reloaded answers.
  std::optional<wire::ServerMessage> outcomeOf(OutcomeBook::Key key, bool journalFailed) const;

 private:
  struct Recorder {
    std::weak_ptr<Subscriber> who;
    uint64_t fromVersion;  // its subscribe's Ack version: later commands only
  };
  void ack(const PendingEdit& edit);
  void notifyRecorders(const PendingEdit& edit);

  const store::DocumentId document_;
  const uint32_t maxFrameBytes_;
  ServerStats& stats_;
  uint64_t durableVersion_;
  uint64_t ackedVersion_;  // the newest edit whose Ack was sent
  std::deque<PendingEdit> pending_;
  std::deque<FlushBatch> batches_;
  std::map<uint64_t, Recorder> recorders_;  // by session
  OutcomeBook outcomes_;
};

}  // namespace tessera::server
