#include "server/document/document_host.h"

#include <unistd.h>
#include <algorithm>
#include <boost/asio/bind_executor.hpp>
#include <boost/asio/post.hpp>
#include <cmath>
#include <filesystem>

#include "core/io/mesh_export.h"
#include "core/morph/keyed_document_file.h"
#include "core/tessellation/document_grid.h"
#include "core/util/file_io.h"
#include "protocol/framing.h"
#include "protocol/utf8_text.h"
#include "server/base/log.h"
#include "server/document/journal_entry.h"
#include "server/document/profile_request.h"
#include "server/document/replies.h"

namespace tessera::server {

namespace {

using Clock = std::chrono::steady_clock;

// Snapshot parts stay well under any client's frame limit.
constexpr size_t kSnapshotPartBytes = 4u << 20;

}  // namespace

void DocumentHost::onUndecided(std::function<void(Undecided)> handler) {
  std::lock_guard<std::mutex> lock(undecidedMutex_);
  undecidedHandler_ = std::move(handler);
}

void DocumentHost::setLoadedOutcomes(std::map<OutcomeBook::Key, CommandOutcome> outcomes,
                                     uint64_t fromVersion) {
  queue_.post(Lane::kInteractive,
              [self = shared_from_this(), outcomes = std::move(outcomes), fromVersion]() mutable {
                self->commits_.setLoadedOutcomes(std::move(outcomes), fromVersion);
              });
}

void DocumentHost::answerOutcomes(std::shared_ptr<Subscriber> who, std::vector<uint64_t> clientSeqs) {
  queue_.post(Lane::kInteractive, [self = shared_from_this(), who, clientSeqs = std::move(clientSeqs)] {
    for (uint64_t seq : clientSeqs) {
      auto answer = self->commits_.outcomeOf({who->sessionId(), seq}, self->journalFailed_);
      if (answer) who->send({frameOf(*answer, self->config_.limits.maxFrameBytes), nullptr});
    }
  });
}

DocumentHost::DocumentHost(store::DocumentId id, std::string name, KeyedDocument doc, uint64_t version,
                           boost::asio::any_io_executor workers, boost::asio::any_io_executor bulk,
                           store::Store& store, const ServerConfig& config, ServerStats& stats)
    : id_(id),
      name_(std::move(name)),
      doc_(std::move(doc)),
      version_(version),
      lastSnapshot_(version),
      flushedVersion_(version),
      counts_(doc_.key0().counts()),
      bulk_(bulk),
      queue_(workers, bulk),
      presenceTimer_(workers),
      store_(store),
      config_(config),
      stats_(stats),
      flushTimer_(workers),
      commits_(id, version, config.limits.maxFrameBytes, stats) {
  auto grid = documentGrid(doc_.key0());
  if (grid.isOk()) grid_ = *grid;
}

DocumentHost::~DocumentHost() {
  // Freeing a large document takes seconds: the document and its views go
  // on a bulk thread, which then trims the heap, rather than on the worker
  // that dropped the last reference (it may owe a small document an edit).
  releaseOnBulk(std::make_shared<Released>(Released{std::move(doc_), std::move(views_)}));
  logEvent(LogLevel::kInfo, "document_closed", {{"doc", id_.value}});
}

void DocumentHost::subscribe(std::shared_ptr<Subscriber> who, const wire::LodProfile& requested,
                             uint64_t clientSeq, bool resync, bool withCommands) {
  // Refused from the estimate before any work, on the caller's thread: a
  // profile whose base level alone is over its budget (docs/PROTOCOL.md §9).
  const int64_t least = minimumTriangles(requested);
  const int64_t budget = budgetOf(requested, config_.limits);
  if (least > budget) {
    who->send({limitExceeded(clientSeq,
                             "LOD profile: base level " + std::to_string(requested.base_level()) +
                                 " alone has " + std::to_string(least) + " triangles, above the budget of " +
                                 std::to_string(budget),
                             config_.limits.maxFrameBytes),
               nullptr});
    return;
  }
  queue_.post(laneFor(maximumTriangles(requested)), [self = shared_from_this(), who, requested, clientSeq,
                                                     resync, withCommands] {
    // The snapshot is taken at version_: every view's encodings must reach it.
    self->flush();
    const Limits& limits = self->config_.limits;
    auto checked = checkProfileRequest(requested, limits, self->id_, self->doc_.key0().options().maxLevel,
                                       self->doc_.isMorph());
    if (!checked.isOk()) {
      who->send({frameOf(rejectFor(clientSeq, checked.status()), limits.maxFrameBytes), nullptr});
      return;
    }
    const LodProfile& profile = checked->profile;
    const std::optional<double>& morphT = checked->morphT;
    const std::string& key = checked->key;
    auto it = self->views_.find(key);
    // The views left if this subscriber moves to `key`: those someone else
    // still watches. Counted before anything changes, so that a refused
    // profile leaves the subscriber on the one it had.
    size_t kept = 0;
    for (const auto& [other, view] : self->views_) {
      kept += std::any_of(view.subscribers.begin(), view.subscribers.end(),
                          [&](const auto& s) { return s.first != who->sessionId() && !s.second.expired(); })
                  ? 1
                  : 0;
    }
    if (it == self->views_.end() && kept >= static_cast<size_t>(limits.profilesPerDocument)) {
      // Every view is re-tessellated on every edit: their number is capped.
      who->send(
          {limitExceeded(clientSeq,
                         "document " + std::to_string(self->id_.value) + " already serves " +
                             std::to_string(self->views_.size()) +
                             " LOD profiles, the limit (--profiles-per-document); subscribe with one of them",
                         limits.maxFrameBytes),
           nullptr});
      return;
    }
    if (it == self->views_.end()) {
      const auto start = Clock::now();
      Expected<View> built = morphT ? self->buildMorphView(*morphT, profile) : Expected<View>(View{});
      if (built.isOk() && !morphT) {
        auto tessellation = Tessellation::build(self->doc_.growableKey0(), profile);
        if (tessellation.isOk()) {
          built->tessellation = std::make_unique<Tessellation>(std::move(*tessellation));
        } else {
          built = tessellation.status();
        }
      }
      self->stats_.tessellateMicros += microsSince(start);
      self->stats_.tessellateLatency.addMicros(microsSince(start));
      if (!built.isOk()) {
        // Over the budget, or a morph whose keys do not match (the error says where).
        const Status& why = built.status();
        who->send({why.code() == ErrorCode::kInvalidArgument
                       ? frameOf(rejectFor(clientSeq, why), self->config_.limits.maxFrameBytes)
                       : limitExceeded(clientSeq, why.message(), self->config_.limits.maxFrameBytes),
                   nullptr});
        return;
      }
      View view = std::move(*built);
      view.wireProfile = requested;
      for (const auto& [region, mesh] : view.tessellation->regions()) {
        view.layout[region] = self->version_;
        rehashRegion(view, region, self->grid_);
      }
      self->leaveOtherViews(who->sessionId(), key);
      it = self->views_.emplace(key, std::move(view)).first;
    } else {
      self->leaveOtherViews(who->sessionId(), key);
      it = self->views_.find(key);  // still there: watched by others, or by this subscriber
    }
    View& view = it->second;
    if (!resync) {
      wire::ServerMessage ack = ackFor(clientSeq, self->id_.value);
      ack.mutable_ack()->set_version(self->version_);
      who->send({frameOf(ack, self->config_.limits.maxFrameBytes), nullptr});
      if (withCommands) {
        self->commits_.record(who->sessionId(), who, self->version_);
      } else {
        self->commits_.stopRecording(who->sessionId());
      }
    }
    self->sendSnapshot(view, who, resync);
    // Other views may have rebuilt (the hierarchy can grow); their next
    // update notices it by itself.
  });
}

void DocumentHost::unsubscribe(uint64_t session) {
  queue_.post(Lane::kInteractive, [self = shared_from_this(), session] {
    self->commits_.stopRecording(session);
    for (auto& [key, view] : self->views_) view.subscribers.erase(session), view.knownVersion.erase(session);
    self->dropUnwatchedViews();
  });
}

void DocumentHost::sendSnapshot(View& view, const std::shared_ptr<Subscriber>& who, bool resync) {
  for (auto& frame : snapshotFrames(view, id_.value, resync, encodeContext(view), kSnapshotPartBytes,
                                    config_.limits.maxFrameBytes)) {
    who->send({frame, nullptr, id_.value});
  }
  view.subscribers[who->sessionId()] = who;
  view.knownVersion[who->sessionId()] = version_;
  view.lastUsed = ++useClock_;
  if (resync) ++stats_.resyncs;
}

void DocumentHost::command(std::shared_ptr<Subscriber> author, std::string authorName,
                           wire::ClientMessage message) {
  // A second key's mesh is imported on the bulk lane when it is large.
  const Lane lane = message.has_add_morph_key() && message.add_morph_key().mesh().size() > (1u << 20)
                        ? Lane::kBulk
                        : Lane::kInteractive;
  queue_.post(lane, [self = shared_from_this(), author, authorName = std::move(authorName),
                     message = std::move(message)] {
    const uint64_t seq = message.client_seq();
    if (self->failed_) {
      author->send({frameOf(rejectFor(seq, internalError("the document's journal failed (" +
                                                         self->journalFailure_.message() + "); reopen it")),
                            self->config_.limits.maxFrameBytes),
                    nullptr});
      return;
    }
    AppliedChange applied;
    Status status = applyCommand(self->doc_, self->id_, message, applied);
    if (!status.isOk()) {
      ++self->stats_.rejects;
      author->send({frameOf(rejectForCommand(seq, message, applied.failedIndex, status),
                            self->config_.limits.maxFrameBytes),
                    nullptr});
      return;
    }
    self->afterApply(author, seq, applied, authorName, message);
  });
}

void DocumentHost::afterApply(const std::shared_ptr<Subscriber>& author, uint64_t clientSeq,
                              const AppliedChange& applied, const std::string& authorName,
                              const wire::ClientMessage& command) {
  const JournalEntry& entry = applied.entry;
  // An edit that moves the surface out of the document's quantization grid
  // is taken back and refused before anything is sent: every displayed
  // vertex is a hierarchy limit, and the changed ones are listed.
  bool outside = false;
  for (uint32_t key = 0; key < doc_.numKeys(); ++key) {
    const SparseHierarchy& h = doc_.key(key).hierarchy();
    for (VertexId id : key == 0 ? applied.limits : applied.key1Limits) {
      if (id.level() >= h.numLevels()) continue;  // a batch's later undo dropped the level: its limit is gone
      const Index v = h.level(id.level()).findVertex(id.index());
      if (v == kNoIndex) continue;
      outside = outside || !grid_.contains(h.limitPosition(id.level(), v));
    }
  }
  if (outside) {
    Status back = retractCommand(doc_, entry);
    ++stats_.rejects;
    if (!back.isOk())
      logEvent(LogLevel::kError, "retract_failed", {{"doc", id_.value}, {"error", back.message()}});
    author->send(
        {limitExceeded(clientSeq,
                       "the edit would move the surface outside the document's bounds: the cube from (" +
                           std::to_string(grid_.origin[0]) + ", " + std::to_string(grid_.origin[1]) + ", " +
                           std::to_string(grid_.origin[2]) + ") with side " + std::to_string(grid_.range),
                       config_.limits.maxFrameBytes),
         nullptr});
    return;
  }
  stats_.edits += applied.editIds.size();  // a batch's commands count one by one; its version once
  ++version_;
  commits_.applied({version_, author, author->sessionId(), clientSeq, applied.editIds.back(),
                    command.has_edit_batch() ? applied.editIds : std::vector<uint64_t>{}, Clock::now(),
                    command, authorName});
  changedLimits_.insert(changedLimits_.end(), applied.limits.begin(), applied.limits.end());
  keysChanged_ = keysChanged_ || doc_.isMorph();
  // The flush and the commit may finish in either order: each calls
  // release(), which sends a batch once its last edit is durable.
  scheduleFlush();
  store_.appendFrom(id_, version_ - 1, authorName, author->sessionId(), clientSeq, encodeJournalEntry(entry),
                    [self = shared_from_this(), version = version_](Status status) {
                      self->queue_.post(Lane::kInteractive,
                                        [self, version, status] { self->committed(version, status); });
                    });
}

// A flush waits until the pacing interval after the last one has passed:
// the edits meanwhile share its delta. The interval is the larger of
// --delta-interval-ms and subscribers / --delta-frames-per-second, so the
// frames a document fans out per second stay bounded (every delta re-sends
// whole regions to every subscriber) at the cost of at most that interval
// of latency, and only under load: an edit after a quiet spell goes at once.
Clock::duration DocumentHost::flushInterval() const {
  double ms = config_.deltaIntervalMs;
  if (config_.deltaFramesPerSecond > 0) {
    size_t subscribers = 0;
    for (const auto& [key, view] : views_) subscribers += view.subscribers.size();
    ms = std::max(ms, 1000.0 * static_cast<double>(subscribers) / config_.deltaFramesPerSecond);
  }
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(ms));
}

void DocumentHost::scheduleFlush() {
  if (flushScheduled_) return;
  flushScheduled_ = true;
  const auto due = lastFlush_ + flushInterval();
  if (Clock::now() >= due) {
    queue_.post(Lane::kInteractive, [self = shared_from_this()] { self->flush(); });
    return;
  }
  flushTimer_.expires_at(due);
  flushTimer_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
    if (ec != boost::asio::error::operation_aborted)
      self->queue_.post(Lane::kInteractive, [self] { self->flush(); });
  });
}

void DocumentHost::flush() {
  flushScheduled_ = false;
  if (version_ == flushedVersion_) return;
  std::sort(changedLimits_.begin(), changedLimits_.end());
  changedLimits_.erase(std::unique(changedLimits_.begin(), changedLimits_.end()), changedLimits_.end());
  // After a failed journal write the edits are lost: views still follow
  // the document, but nothing is sent.
  // Kept morph views nobody watches are stale now: dropped, not rebuilt.
  if (keysChanged_) dropRetainedMorphViews();
  const PendingEdit* last = commits_.newest();
  FlushBatch batch{version_, {}, {}};
  if (last) ++stats_.deltaFlushes;
  for (auto it = views_.begin(); it != views_.end();) {
    View& view = it->second;
    const auto start = Clock::now();
    auto changes = view.morphT ? (keysChanged_ ? rebuildMorphView(view)
                                               : Expected<Tessellation::Changes>(Tessellation::Changes{}))
                               : view.tessellation->update(doc_.growableKey0(), changedLimits_);
    stats_.tessellateMicros += microsSince(start);
    stats_.tessellateLatency.addMicros(microsSince(start));
    if (!changes.isOk()) {
      // Over its triangle budget now: its subscribers get an error and the
      // view goes; they may subscribe again with another profile.
      wire::ServerMessage error;
      error.mutable_error()->set_code(wire::ERROR_CODE_INTERNAL);
      error.mutable_error()->set_message("LOD profile " + it->first +
                                         " dropped: " + changes.status().message());
      auto frame = frameOf(error, config_.limits.maxFrameBytes);
      for (auto& [session, weak] : view.subscribers) {
        if (auto who = weak.lock()) who->send({frame, nullptr});
      }
      it = views_.erase(it);
      continue;
    }
    auto delta = std::make_shared<DeltaContent>();
    delta->documentId = id_.value;
    delta->fromVersion = flushedVersion_;
    delta->toVersion = version_;
    delta->authorSession = last ? last->authorSession : 0;
    delta->editId = last ? last->editId : 0;
    buildDelta(view, *changes, encodeContext(view), id_.value, *delta);
    batch.frames[it->first] = encodeDeltaFrame(*delta, config_.limits.maxFrameBytes);
    batch.deltas[it->first] = std::move(delta);
    ++it;
  }
  changedLimits_.clear();
  keysChanged_ = false;
  flushedVersion_ = version_;
  lastFlush_ = Clock::now();
  if (!last) return;
  if (!config_.deltasAfterDurable) send(batch);
  commits_.flushed(std::move(batch));
  release();  // its commit may already be durable
  maybeSnapshot();
}

void DocumentHost::committed(uint64_t version, Status status) {
  if (!status.isOk()) {
    failed_ = true;
    journalFailed_ = true;
    journalFailure_ = status;
    logEvent(LogLevel::kError, "journal_failed",
             {{"doc", id_.value}, {"version", version}, {"error", status.message()}});
    wire::ServerMessage error;
    error.mutable_error()->set_code(wire::ERROR_CODE_INTERNAL);
    error.mutable_error()->set_message("document " + std::to_string(id_.value) +
                                       ": journal write failed: " + status.message());
    auto frame = frameOf(error, config_.limits.maxFrameBytes);
    for (auto& [session, p] : participants_) {
      if (auto who = p.who.lock()) who->send({frame, nullptr});
    }
    // Every edit still waiting for its commit is lost, or, when the store
    // cannot know (outcomeUnknown: a replicated journal timed out), may be
    // stored: those go to whoever reloads the document, which can tell
    // from the journal (onUndecided); the others are refused now.
    std::function<void(Undecided)> handler;
    {
      std::lock_guard<std::mutex> lock(undecidedMutex_);
      handler = undecidedHandler_;
    }
    Undecided undecided = commits_.failed(status, store::outcomeUnknown(status) && handler);
    if (!undecided.empty()) handler(std::move(undecided));
    return;
  }
  commits_.durable(version);
  release();
  maybeSnapshot();
}

void DocumentHost::release() {
  commits_.release([this](FlushBatch& batch) { send(batch); });
}

void DocumentHost::send(FlushBatch& b) {
  for (auto& [key, view] : views_) {
    auto frame = b.frames.find(key);
    if (frame == b.frames.end() || !frame->second) continue;
    for (auto& [session, weak] : view.subscribers) {
      if (view.knownVersion[session] >= b.toVersion) continue;  // its snapshot holds this one
      if (auto who = weak.lock()) who->send({frame->second, b.deltas[key]});
    }
  }
  b.frames.clear();  // the batch stays only to order the recorders' commands
  b.deltas.clear();
}

void DocumentHost::maybeSnapshot() {
  // Only at rest: a snapshot must never hold an edit the journal lacks.
  if (!commits_.atRest(version_) || version_ - lastSnapshot_ < config_.snapshotEvery) return;
  Status saved = store_.putSnapshot(id_, version_ - 1, serializeKeyedDocument(doc_));
  if (!saved.isOk()) {
    logEvent(LogLevel::kWarn, "snapshot_failed", {{"doc", id_.value}, {"error", saved.message()}});
    return;
  }
  lastSnapshot_ = version_;
}

void DocumentHost::exportGlb(std::shared_ptr<Subscriber> who, uint64_t clientSeq,
                             wire::ExportDocument request) {
  // Refused from the exact count before any work (docs/PROTOCOL.md §9).
  const int64_t triangles = uniformTriangles(request.level());
  if (triangles > config_.limits.maxTrianglesPerSubscriber) {
    who->send(
        {limitExceeded(clientSeq,
                       "export: level " + std::to_string(request.level()) + " has " +
                           std::to_string(triangles) + " triangles, above the limit of " +
                           std::to_string(config_.limits.maxTrianglesPerSubscriber) + " (--max-triangles)",
                       config_.limits.maxFrameBytes),
         nullptr});
    return;
  }
  queue_.post(laneFor(triangles), [self = shared_from_this(), who, clientSeq, request, triangles] {
    const uint32_t maxFrame = self->config_.limits.maxFrameBytes;
    auto surface = self->doc_.key0().surface(static_cast<int>(std::min<uint32_t>(request.level(), 64)),
                                             request.limit() ? SurfaceKind::kLimit : SurfaceKind::kControl);
    if (!surface.isOk()) {
      who->send({frameOf(rejectFor(clientSeq, surface.status()), maxFrame), nullptr});
      return;
    }
    // The GLB writer targets files: a private temporary one.
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("tessera-export-" + std::to_string(::getpid()) + "-" +
                               std::to_string(clientSeq) + "-" + std::to_string(who->sessionId()) + ".glb"))
                                 .string();
    ExportOptions options;
    options.draco = request.draco();
    Status written = exportMesh(*surface, path, options);
    Expected<std::string> bytes = written.isOk() ? readFile(path) : Expected<std::string>(written);
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    if (!bytes.isOk()) {
      who->send({frameOf(rejectFor(clientSeq, bytes.status()), maxFrame), nullptr});
      return;
    }
    wire::ServerMessage m;
    wire::ExportResult* r = m.mutable_export_result();
    r->set_client_seq(clientSeq);
    r->set_document_id(self->id_.value);
    r->set_version(self->version_);
    r->set_glb(std::move(*bytes));
    auto frame = frameOf(m, maxFrame);
    if (!frame) {
      who->send(
          {frameOf(rejectFor(clientSeq, invalidArgument("the export exceeds the frame limit")), maxFrame),
           nullptr});
      return;
    }
    who->send({frame, nullptr});
    if (self->laneFor(triangles) == Lane::kBulk) self->trimMemory();
  });
}

}  // namespace tessera::server
