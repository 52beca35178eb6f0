#include "server/document/document_host.h"

#include <unistd.h>
#include <algorithm>
#include <boost/asio/bind_executor.hpp>
#include <boost/asio/post.hpp>
#include <cmath>
#include <filesystem>

#include "core/document/control_cage.h"
#include "core/io/mesh_export.h"
#include "core/morph/keyed_document_file.h"
#include "core/tessellation/document_bounds.h"
#include "core/tessellation/document_grid.h"
#include "core/util/file_io.h"
#include "protocol/framing.h"
#include "protocol/utf8_text.h"
#include "server/base/log.h"
#include "server/document/bulk_release.h"
#include "server/document/document_admission.h"
#include "server/document/journal_entry.h"
#include "server/document/morph_control.h"
#include "server/document/morph_view.h"
#include "server/document/replies.h"
#include "server/document/view_request.h"

namespace tessera::server {

namespace {

using Clock = std::chrono::steady_clock;

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
      presence_(id.value, config.limits.maxFrameBytes),
      store_(store),
      config_(config),
      stats_(stats),
      views_(id, config.limits.maxTrianglesPerSubscriber, config.limits.maxFrameBytes),
      flushTimer_(workers),
      commits_(id, version, config.limits.maxFrameBytes, stats),
      tileStreams_(id.value, config.limits.maxFrameBytes, stats,
                   [this] { return editTasksWaiting_.load(std::memory_order_relaxed) > 0; }),
      viewTimer_(workers) {
  auto grid = documentGrid(doc_.key0());
  if (grid.isOk()) grid_ = *grid;
}

DocumentHost::~DocumentHost() {
  // Freeing a large document takes seconds: the document and its views go
  // on a bulk thread, which then trims the heap, rather than on the worker
  // that dropped the last reference (it may owe a small document an edit).
  releaseOnBulk(bulk_, std::make_shared<Released>(Released{std::move(doc_), views_.takeAll()}));
  logEvent(LogLevel::kInfo, "document_closed", {{"doc", id_.value}});
}

void DocumentHost::subscribe(std::shared_ptr<Subscriber> who, const wire::Subscribe& request,
                             uint64_t clientSeq, bool resync) {
  // An unknown codec, or one views are not served in, is refused naming the
  // field, on the caller's thread (profile_request.h).
  auto codec = codecFromWire(request);
  if (!codec.isOk()) {
    who->send({frameOf(rejectFor(clientSeq, codec.status()), config_.limits.maxFrameBytes), nullptr});
    return;
  }
  if (!request.has_view())
    return subscribeProfile(who, request.profile(), clientSeq, resync, request.with_commands(), *codec);
  // A bad view costs nothing: refused on the caller's thread.
  auto view = viewFromWire(request.view());
  if (!view.isOk()) {
    who->send({frameOf(rejectFor(clientSeq, view.status()), config_.limits.maxFrameBytes), nullptr});
    return;
  }
  // Choosing and encoding the first tiles of a large document is bulk work.
  const Lane lane = laneFor(static_cast<int64_t>(counts_.faces(0)) * 16, config_);
  queue_.post(lane, [self = shared_from_this(), who, request, view = *view, clientSeq, resync] {
    self->subscribeView(who, request, view, clientSeq, resync);
  });
}

void DocumentHost::subscribeView(const std::shared_ptr<Subscriber>& who, const wire::Subscribe& request,
                                 const View& view, uint64_t clientSeq, bool resync) {
  // Tiles are chosen and encoded at version_: every edit before is flushed.
  flush();
  const int64_t budget = budgetOf(request.profile(), config_.limits);
  TileCache& tiles = tileCache();
  // The preview needs no tile tree: it goes before the tree is built and the
  // tiles are chosen, which takes most of a large document's first second,
  // wherever the budget holds every root, the most the coarsest tiles a view
  // needs can be, so that no refusal can follow the Ack (docs/VIEWS.md "The
  // first picture").
  if (tiles.hasPreview()) {
    auto preview = tiles.encoded(TileKey::preview(), version_);
    if (preview.isOk() && tiles.levelZeroTriangles().value_or(budget + 1) <= budget) {
      acceptView(who, request, clientSeq, resync);
      Status sent =
          tileStreams_.open(tiles, who, view, budget, request.profile(), version_, resync, *preview);
      if (sent.isOk()) {
        auto target = tiles.select(view, budget);
        sent =
            target.isOk() ? tileStreams_.start(tiles, who->sessionId(), *target, version_) : target.status();
      }
      if (!sent.isOk()) viewFailed(who, sent);
      return;
    }
  }
  auto target = tiles.select(view, budget);
  if (!target.isOk()) {
    who->send({frameOf(rejectFor(clientSeq, target.status()), config_.limits.maxFrameBytes), nullptr});
    return;
  }
  if (target->triangles > budget) {
    who->send({limitExceeded(clientSeq,
                             "view: the coarsest tiles it needs have " + std::to_string(target->triangles) +
                                 " triangles, above the budget of " + std::to_string(budget),
                             config_.limits.maxFrameBytes),
               nullptr});
    return;
  }
  acceptView(who, request, clientSeq, resync);
  Status sent = tileStreams_.open(tiles, who, view, budget, request.profile(), version_, resync);
  if (sent.isOk()) sent = tileStreams_.start(tiles, who->sessionId(), *target, version_);
  if (!sent.isOk()) viewFailed(who, sent);
}

void DocumentHost::acceptView(const std::shared_ptr<Subscriber>& who, const wire::Subscribe& request,
                              uint64_t clientSeq, bool resync) {
  // One subscription per subscriber and document: a profile it had goes.
  releaseViews(views_.leave(who->sessionId()));
  if (resync) return;
  wire::ServerMessage ack = ackFor(clientSeq, id_.value);
  ack.mutable_ack()->set_version(version_);
  who->send({frameOf(ack, config_.limits.maxFrameBytes), nullptr});
  if (request.with_commands()) {
    commits_.record(who->sessionId(), who, version_);
  } else {
    commits_.stopRecording(who->sessionId());
  }
}

void DocumentHost::viewFailed(const std::shared_ptr<Subscriber>& who, const Status& status) {
  logEvent(LogLevel::kError, "view_failed", {{"doc", id_.value}, {"error", status.message()}});
  wire::ServerMessage error;
  error.mutable_error()->set_code(wire::ERROR_CODE_INTERNAL);
  error.mutable_error()->set_message("document " + std::to_string(id_.value) + ": view: " + status.message());
  who->send({frameOf(error, config_.limits.maxFrameBytes), nullptr});
  tileStreams_.leave(who->sessionId());
}

TileCache& DocumentHost::tileCache() {
  if (!tileCache_)
    tileCache_ = std::make_unique<TileCache>(doc_.growableKey0(), grid_, config_.tileCacheBytes, stats_);
  return *tileCache_;
}

void DocumentHost::setView(std::shared_ptr<Subscriber> who, uint64_t clientSeq, wire::View requested) {
  ++stats_.viewsReceived;
  auto view = viewFromWire(requested);
  if (!view.isOk()) {
    ++stats_.rejects;
    who->send({frameOf(rejectFor(clientSeq, view.status()), config_.limits.maxFrameBytes), nullptr});
    return;
  }
  queue_.post(Lane::kInteractive, [self = shared_from_this(), who, view = *view, clientSeq] {
    if (!self->tileStreams_.has(who->sessionId())) {
      ++self->stats_.rejects;
      who->send({frameOf(rejectFor(clientSeq,
                                   invalidArgument("set view: document " + std::to_string(self->id_.value) +
                                                   " has no view-dependent subscription of this "
                                                   "session; subscribe with a view first")),
                         self->config_.limits.maxFrameBytes),
                 nullptr});
      return;
    }
    self->tileStreams_.setPending(who->sessionId(), view, clientSeq);
    self->scheduleViews();
  });
}

namespace {

Clock::duration viewInterval(const ServerConfig& config) {
  return std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double, std::milli>(config.viewIntervalMs));
}

}  // namespace

void DocumentHost::scheduleViews() {
  if (viewsScheduled_) return;
  const auto due = tileStreams_.nextDue(viewInterval(config_));
  if (!due) return;
  viewsScheduled_ = true;
  if (Clock::now() >= *due) {
    queue_.postWhenIdle([self = shared_from_this()] { self->applyViews(); });
    return;
  }
  viewTimer_.expires_at(*due);
  viewTimer_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
    if (ec != boost::asio::error::operation_aborted)
      self->queue_.postWhenIdle([self] { self->applyViews(); });
  });
}

void DocumentHost::applyViews() {
  viewsScheduled_ = false;
  flush();  // tiles are chosen at version_
  if (tileCache_) tileStreams_.applyDue(*tileCache_, Clock::now(), viewInterval(config_), version_);
  scheduleViews();
}

void DocumentHost::scheduleSettle() {
  if (settleScheduled_ || !tileStreams_.unsettled()) return;
  settleScheduled_ = true;
  queue_.postWhenIdle([self = shared_from_this()] { self->settleViews(); });
}

void DocumentHost::settleViews() {
  flush();  // tiles are chosen at version_; its edits settle now too
  settleScheduled_ = false;
  if (tileCache_ && !tileStreams_.settle(*tileCache_, version_)) scheduleSettle();  // after the edit
  scheduleViews();  // the views settle left incomplete go on
}

void DocumentHost::subscribeProfile(const std::shared_ptr<Subscriber>& who, const wire::LodProfile& requested,
                                    uint64_t clientSeq, bool resync, bool withCommands, RegionCodec codec) {
  // Refused from the estimate before any work, on the caller's thread: a
  // profile whose base level alone is over its budget (docs/PROTOCOL.md §9).
  const int64_t least = minimumTriangles(counts_, requested);
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
  const Lane lane = laneFor(maximumTriangles(counts_, requested, config_.limits), config_);
  queue_.post(lane, [self = shared_from_this(), who, requested, clientSeq, resync, withCommands, codec] {
    // The snapshot is taken at version_: every view's encodings must reach it.
    self->flush();
    self->tileStreams_.leave(who->sessionId());  // a view it had goes
    const Limits& limits = self->config_.limits;
    auto checked = checkProfileRequest(requested, limits, self->id_, self->doc_.key0().options().maxLevel,
                                       self->doc_.isMorph());
    if (!checked.isOk()) {
      who->send({frameOf(rejectFor(clientSeq, checked.status()), limits.maxFrameBytes), nullptr});
      return;
    }
    const std::string& key = checked->key;
    LodView* view = self->views_.find(key);
    // The views left if this subscriber moves to `key`: those someone else
    // still watches. Counted before anything changes, so that a refused
    // profile leaves the subscriber on the one it had.
    const size_t kept = self->views_.watchedByOthers(who->sessionId());
    if (!view && kept >= static_cast<size_t>(limits.profilesPerDocument)) {
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
    if (!view) {
      Expected<LodView> built = self->buildView(*checked, requested);
      if (!built.isOk()) {
        // Over the budget, or a morph whose keys do not match (the error says where).
        const Status& why = built.status();
        who->send({why.code() == ErrorCode::kInvalidArgument
                       ? frameOf(rejectFor(clientSeq, why), self->config_.limits.maxFrameBytes)
                       : limitExceeded(clientSeq, why.message(), self->config_.limits.maxFrameBytes),
                   nullptr});
        return;
      }
      self->releaseViews(self->views_.leaveAllBut(who->sessionId(), key));
      view = &self->views_.add(key, std::move(*built));
    } else {
      self->releaseViews(self->views_.leaveAllBut(who->sessionId(), key));
      view = self->views_.find(key);  // still there: watched by others, or by this subscriber
    }
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
    self->sendSnapshot(*view, who, resync, codec);
    // Other views may have rebuilt (the hierarchy can grow); their next
    // update notices it by itself.
  });
}

Expected<LodView> DocumentHost::buildView(const ProfileRequest& checked, const wire::LodProfile& requested) {
  const auto start = Clock::now();
  Expected<LodView> built =
      checked.morphT ? buildMorphView(doc_, *checked.morphT, checked.profile) : Expected<LodView>(LodView{});
  if (built.isOk() && !checked.morphT) {
    auto tessellation = Tessellation::build(doc_.growableKey0(), checked.profile);
    if (tessellation.isOk()) {
      built->tessellation = std::make_unique<Tessellation>(std::move(*tessellation));
    } else {
      built = tessellation.status();
    }
  }
  stats_.tessellateMicros += microsSince(start);
  stats_.tessellateLatency.addMicros(microsSince(start));
  if (!built.isOk()) return built;
  built->wireProfile = requested;
  for (const auto& [region, mesh] : built->tessellation->regions()) {
    built->layout[region] = version_;
    rehashRegion(*built, region, grid_);
  }
  return built;
}

void DocumentHost::unsubscribe(uint64_t session) {
  queue_.post(Lane::kInteractive, [self = shared_from_this(), session] {
    self->commits_.stopRecording(session);
    self->releaseViews(self->views_.leave(session));
    self->tileStreams_.leave(session);
  });
}

void DocumentHost::sendSnapshot(LodView& view, const std::shared_ptr<Subscriber>& who, bool resync,
                                RegionCodec codec) {
  for (auto& frame : snapshotFrames(view, id_.value, resync, encodeContext(view), kSnapshotPartBytes,
                                    config_.limits.maxFrameBytes, codec)) {
    who->send({frame, nullptr, id_.value});
  }
  views_.attach(view, who, version_, codec);
  if (resync) ++stats_.resyncs;
}

void DocumentHost::releaseViews(DocumentViews::Views dropped) {
  if (!dropped.empty()) releaseOnBulk(bulk_, std::make_shared<DocumentViews::Views>(std::move(dropped)));
}

// Presence changes within 100 ms share one broadcast (document_presence.h).
void DocumentHost::presenceChanged() {
  if (presencePending_) return;
  presencePending_ = true;
  presenceTimer_.expires_after(std::chrono::milliseconds(100));
  presenceTimer_.async_wait([self = shared_from_this()](const boost::system::error_code&) {
    self->queue_.post(Lane::kInteractive, [self] {
      self->presencePending_ = false;
      self->presence_.broadcast();
    });
  });
}

void DocumentHost::join(std::shared_ptr<Subscriber> who, std::string name, wire::Role role) {
  queue_.post(Lane::kInteractive, [self = shared_from_this(), who, name = std::move(name), role] {
    self->presence_.join(who, name, role);
    self->presenceChanged();
  });
}

void DocumentHost::leave(uint64_t session) {
  queue_.post(Lane::kInteractive, [self = shared_from_this(), session] {
    self->presence_.leave(session);
    self->commits_.stopRecording(session);
    self->releaseViews(self->views_.leave(session));
    self->tileStreams_.leave(session);
    self->presenceChanged();
  });
}

void DocumentHost::select(std::shared_ptr<Subscriber> who, uint64_t clientSeq, wire::Selection selection) {
  queue_.post(Lane::kInteractive,
              [self = shared_from_this(), who, clientSeq, selection = std::move(selection)] {
                if (!self->presence_.isParticipant(who->sessionId())) return;
                Status valid = checkSelection(selection, self->counts_, self->config_.limits);
                if (!valid.isOk()) {
                  who->send({frameOf(rejectFor(clientSeq, valid.withContext("selection of document " +
                                                                            std::to_string(self->id_.value))),
                                     self->config_.limits.maxFrameBytes),
                             nullptr});
                  return;
                }
                self->presence_.select(who->sessionId(), selection);
                self->presenceChanged();
              });
}

void DocumentHost::resendPresence(uint64_t session) {
  queue_.post(Lane::kInteractive, [self = shared_from_this(), session] {
    if (self->presence_.resendTo(session)) self->presenceChanged();
  });
}

void DocumentHost::command(std::shared_ptr<Subscriber> author, std::string authorName,
                           wire::ClientMessage message) {
  // A second key's mesh is imported on the bulk lane when it is large.
  const Lane lane = message.has_add_morph_key() && message.add_morph_key().mesh().size() > (1u << 20)
                        ? Lane::kBulk
                        : Lane::kInteractive;
  postEditTask(lane, [self = shared_from_this(), author, authorName = std::move(authorName),
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
  // The document's bounds (core/tessellation/document_bounds.h): read on
  // limits the history alone determines, never on what viewers made the
  // hierarchy hold, so every server and every replay decides alike.
  Status bounds = checkWithinBounds(doc_.key(0).hierarchy(), applied.limits, grid_);
  if (bounds.isOk() && doc_.numKeys() > 1)
    bounds = checkWithinBounds(doc_.key(1).hierarchy(), applied.key1Limits, grid_);
  if (!bounds.isOk()) {
    Status back = retractCommand(doc_, entry);
    ++stats_.rejects;
    if (!back.isOk())
      logEvent(LogLevel::kError, "retract_failed", {{"doc", id_.value}, {"error", back.message()}});
    author->send({limitExceeded(clientSeq, bounds.message(), config_.limits.maxFrameBytes), nullptr});
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
                      self->postEditTask(Lane::kInteractive,
                                         [self, version, status] { self->committed(version, status); });
                    });
}

void DocumentHost::postEditTask(Lane lane, std::function<void()> task) {
  editTasksWaiting_.fetch_add(1, std::memory_order_relaxed);
  queue_.post(lane, [this, task = std::move(task)] {
    editTasksWaiting_.fetch_sub(1, std::memory_order_relaxed);
    task();  // it holds the host
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
    const size_t subscribers = views_.subscriberCount();
    ms = std::max(ms, 1000.0 * static_cast<double>(subscribers) / config_.deltaFramesPerSecond);
  }
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(ms));
}

void DocumentHost::scheduleFlush() {
  if (flushScheduled_) return;
  flushScheduled_ = true;
  const auto due = lastFlush_ + flushInterval();
  if (Clock::now() >= due) {
    postEditTask(Lane::kInteractive, [self = shared_from_this()] { self->flush(); });
    return;
  }
  flushTimer_.expires_at(due);
  flushTimer_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
    if (ec != boost::asio::error::operation_aborted)
      self->postEditTask(Lane::kInteractive, [self] { self->flush(); });
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
  if (keysChanged_) releaseViews(views_.dropRetainedMorphViews());
  const PendingEdit* last = commits_.newest();
  FlushBatch batch{version_, {}, {}};
  if (last) ++stats_.deltaFlushes;
  // A view over its triangle budget now goes, its subscribers told why
  // (DocumentViews::updateEach).
  views_.updateEach([&](const std::string& key, LodView& view) -> Status {
    const auto start = Clock::now();
    auto changes = view.morphT ? (keysChanged_ ? rebuildMorphView(doc_, view, grid_)
                                               : Expected<Tessellation::Changes>(Tessellation::Changes{}))
                               : view.tessellation->update(doc_.growableKey0(), changedLimits_);
    stats_.tessellateMicros += microsSince(start);
    stats_.tessellateLatency.addMicros(microsSince(start));
    if (!changes.isOk()) return changes.status();
    DeltaContent base;
    base.documentId = id_.value;
    base.fromVersion = flushedVersion_;
    base.toVersion = version_;
    base.authorSession = last ? last->authorSession : 0;
    base.editId = last ? last->editId : 0;
    // One delta per codec the view's subscribers hold (lod_view.h).
    for (auto& [codec, content] : buildDeltas(view, *changes, encodeContext(view), id_.value, base)) {
      auto delta = std::make_shared<const DeltaContent>(std::move(content));
      const std::string frameKey = deltaKey(key, codec);
      batch.frames[frameKey] = encodeDeltaFrame(*delta, config_.limits.maxFrameBytes);
      batch.deltas[frameKey] = std::move(delta);
    }
    return Status::ok();
  });
  // View-dependent subscribers: the tiles the edits reached are forgotten
  // and each stream chooses again (tile_streams.h). A new key may have
  // moved key 0 in memory: the cache starts again on it.
  std::vector<TileKey> reached;
  if (tileCache_ && keysChanged_) {
    tileCache_.reset();
    tileStreams_.forgetAllTiles();
  } else if (tileCache_) {
    reached = tileCache_->invalidate(changedLimits_);
  }
  if (last && tileStreams_.size() > 0) {
    tileStreams_.afterEdit(tileCache(), reached, flushedVersion_, version_, last->authorSession,
                           last->editId);
    scheduleSettle();
  }
  changedLimits_.clear();
  keysChanged_ = false;
  flushedVersion_ = version_;
  lastFlush_ = Clock::now();
  if (!last) return;
  if (!config_.deltasAfterDurable) views_.send(batch);
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
    presence_.sendToAll(frameOf(error, config_.limits.maxFrameBytes));
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
  commits_.release([this](FlushBatch& batch) { views_.send(batch); });
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
  const int64_t triangles = uniformTriangles(counts_, request.level());
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
  const Lane lane = laneFor(triangles, config_);
  queue_.post(lane, [self = shared_from_this(), who, clientSeq, request, lane] {
    who->send({replyOrReject(clientSeq, self->exportMessage(clientSeq, who->sessionId(), request),
                             self->config_.limits.maxFrameBytes, "the export exceeds the frame limit"),
               nullptr});
    if (lane == Lane::kBulk) trimHeapOnBulk(self->bulk_);
  });
}

Expected<wire::ServerMessage> DocumentHost::exportMessage(uint64_t clientSeq, uint64_t sessionId,
                                                          const wire::ExportDocument& request) const {
  auto surface = doc_.key0().surface(static_cast<int>(std::min<uint32_t>(request.level(), 64)),
                                     request.limit() ? SurfaceKind::kLimit : SurfaceKind::kControl);
  if (!surface.isOk()) return surface.status();
  // The GLB writer targets files: a private temporary one.
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("tessera-export-" + std::to_string(::getpid()) + "-" +
                             std::to_string(clientSeq) + "-" + std::to_string(sessionId) + ".glb"))
                               .string();
  ExportOptions options;
  options.draco = request.draco();
  Status written = exportMesh(*surface, path, options);
  Expected<std::string> bytes = written.isOk() ? readFile(path) : Expected<std::string>(written);
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  if (!bytes.isOk()) return bytes.status();
  wire::ServerMessage m;
  wire::ExportResult* r = m.mutable_export_result();
  r->set_client_seq(clientSeq);
  r->set_document_id(id_.value);
  r->set_version(version_);
  r->set_glb(std::move(*bytes));
  return m;
}

void DocumentHost::morphControl(std::shared_ptr<Subscriber> who, uint64_t clientSeq,
                                wire::GetMorphControl request) {
  queue_.post(Lane::kInteractive, [self = shared_from_this(), who, clientSeq, request] {
    who->send(
        {replyOrReject(clientSeq,
                       morphControlMessage(self->doc_, self->id_.value, self->version_, clientSeq, request),
                       self->config_.limits.maxFrameBytes, "the morph control exceeds the frame limit"),
         nullptr});
  });
}

void DocumentHost::cage(std::shared_ptr<Subscriber> who, uint64_t clientSeq, wire::GetCage request) {
  const uint32_t maxFrame = config_.limits.maxFrameBytes;
  const uint32_t level = request.level();
  const int maxLevel = doc_.key0().options().maxLevel;
  if (level > static_cast<uint32_t>(maxLevel)) {
    who->send({frameOf(rejectFor(clientSeq,
                                 invalidArgument("control cage of document " + std::to_string(id_.value) +
                                                 ": level " + std::to_string(level) + " is outside 0.." +
                                                 std::to_string(maxLevel))),
                       maxFrame),
               nullptr});
    return;
  }
  // A cage has a face for each of the level's faces: the export's bound.
  const int64_t faces = static_cast<int64_t>(counts_.faces(static_cast<int>(level)));
  if (faces > config_.limits.maxTrianglesPerSubscriber) {
    who->send({limitExceeded(clientSeq,
                             "control cage: level " + std::to_string(level) + " has " +
                                 std::to_string(faces) + " faces, above the limit of " +
                                 std::to_string(config_.limits.maxTrianglesPerSubscriber) +
                                 " (--max-triangles); ask for a coarser level",
                             maxFrame),
               nullptr});
    return;
  }
  const Lane lane = laneFor(faces, config_);
  queue_.post(lane, [self = shared_from_this(), who, clientSeq, level, lane] {
    who->send(
        {replyOrReject(clientSeq, self->cageMessage(clientSeq, level), self->config_.limits.maxFrameBytes,
                       "control cage of level " + std::to_string(level) +
                           " exceeds the frame limit; ask for a coarser level"),
         nullptr});
    if (lane == Lane::kBulk) trimHeapOnBulk(self->bulk_);
  });
}

Expected<wire::ServerMessage> DocumentHost::cageMessage(uint64_t clientSeq, uint32_t level) const {
  auto cage = controlCage(doc_.key0(), static_cast<int>(level));
  if (!cage.isOk()) return cage.status();
  wire::ServerMessage m;
  wire::Cage* c = m.mutable_cage();
  c->set_client_seq(clientSeq);
  c->set_document_id(id_.value);
  c->set_version(version_);
  c->set_level(level);
  c->mutable_face_sizes()->Add(cage->faceSizes.begin(), cage->faceSizes.end());
  c->mutable_vertices()->Add(cage->vertices.begin(), cage->vertices.end());
  return m;
}

}  // namespace tessera::server
