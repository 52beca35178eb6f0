#include "server/document/tile_streams.h"

#include <algorithm>
#include <set>
#include <utility>

#include "server/base/log.h"
#include "server/document/replies.h"

namespace tessera::server {

namespace {

// Tiles per delta: about this many bytes, so that the first tiles of a
// large move reach the viewer while the server encodes the rest, and a
// queue that falls behind merges or drops whole deltas (net/outbox.h).
constexpr size_t kChunkBytes = 256u << 10;

// Views applied in one turn of the document's queue: a round of a hundred
// moving cameras would otherwise hold it for tens of milliseconds while
// edits wait behind (docs/VIEWS.md "The server").
constexpr size_t kViewsPerTurn = 8;

// Tiles one turn of views may build (tile_selection.h): a camera that
// reaches new parts of the document, or its first walk, would otherwise
// hold the queue for as long as growing the hierarchy there takes, and an
// edit that comes meanwhile with it (docs/VIEWS.md "The server").
constexpr int64_t kNewTilesPerTurn = 4;

}  // namespace

TileStreams::~TileStreams() {
  stats_.viewSubscribers -= static_cast<int64_t>(streams_.size());
}

Status TileStreams::open(TileCache& tiles, const std::shared_ptr<Subscriber>& who, const View& view,
                         int64_t budget, const wire::LodProfile& profile, uint64_t version, bool resync,
                         std::optional<EncodedTile> preview) {
  Stream s;
  s.who = who;
  s.view = view;
  s.budget = budget;
  s.lastApplied = Clock::now();
  // The first picture, in one snapshot: the surface's preview, a few
  // kilobytes, where it pays; the roots, the coarsest whole surface, where
  // they are as small (docs/VIEWS.md "The first picture").
  std::vector<TileKey> first =
      tiles.hasPreview() ? std::vector<TileKey>{TileKey::preview()} : tiles.tree().roots();
  std::vector<std::pair<uint64_t, std::shared_ptr<const std::string>>> payloads;
  for (const TileKey& key : first) {
    EncodedTile tile;
    if (key.isPreview() && preview) {
      tile = std::move(*preview);
    } else {
      TESSERA_ASSIGN_OR_RETURN(tile, tiles.encoded(key, version));
    }
    s.held[key] = {tile.hash, false};
    s.surfaceHash += tile.hash;
    payloads.emplace_back(key.regionId(), tile.bytes);
  }
  for (auto& frame : encodeSnapshotFrames({documentId_, version, profile, resync, s.surfaceHash}, payloads,
                                          kSnapshotPartBytes, maxFrameBytes_)) {
    who->send({frame, nullptr, documentId_});
  }
  if (!streams_.count(who->sessionId())) ++stats_.viewSubscribers;
  streams_[who->sessionId()] = std::move(s);
  if (resync) ++stats_.resyncs;
  return Status::ok();
}

Status TileStreams::start(TileCache& tiles, uint64_t session, const TileSelection& target, uint64_t version) {
  auto found = streams_.find(session);
  if (found == streams_.end())
    return internalError("view of session " + std::to_string(session) + " was not opened");
  return moveTo(tiles, found->second, target, version, version, 0, 0, /*announce=*/true);
}

void TileStreams::leave(uint64_t session) {
  if (streams_.erase(session)) --stats_.viewSubscribers;
}

void TileStreams::setPending(uint64_t session, const View& view, uint64_t clientSeq) {
  auto found = streams_.find(session);
  if (found == streams_.end()) return;
  found->second.pending = view;
  found->second.pendingSeq = clientSeq;
  found->second.continuing = false;
}

std::optional<TileStreams::Clock::time_point> TileStreams::nextDue(Clock::duration interval) const {
  std::optional<Clock::time_point> due;
  for (const auto& [session, s] : streams_) {
    if (!s.pending) continue;
    // A view the allowance held back goes on at once (continueIncomplete).
    const Clock::time_point at = s.continuing ? Clock::time_point{} : s.lastApplied + interval;
    if (!due || at < *due) due = at;
  }
  return due;
}

void TileStreams::dropGone() {
  for (auto it = streams_.begin(); it != streams_.end();) {
    if (it->second.who.expired()) {
      it = streams_.erase(it);
      --stats_.viewSubscribers;
    } else {
      ++it;
    }
  }
}

void TileStreams::moveEach(TileCache& tiles, const std::vector<Stream*>& moving, uint64_t fromVersion,
                           uint64_t toVersion, uint64_t authorSession, uint64_t editId, bool announce,
                           int64_t newTiles) {
  if (moving.empty()) return;
  std::vector<View> views;
  std::vector<int64_t> budgets;
  for (const Stream* s : moving) views.push_back(s->view), budgets.push_back(s->budget);
  // One walk for every stream: the hierarchy grows once per level for all.
  // A walk with an allowance is a turn of its own: it also stops building
  // once an edit waits behind it. A flush's walk is the edit's own work.
  auto targets =
      tiles.selectForEach(views, budgets, newTiles, newTiles >= 0 ? editsWait_ : std::function<bool()>{});
  for (size_t i = 0; i < moving.size(); ++i) {
    Status moved = targets.isOk() ? moveTo(tiles, *moving[i], (*targets)[i], fromVersion, toVersion,
                                           authorSession, editId, announce)
                                  : targets.status();
    if (!moved.isOk()) {
      logEvent(LogLevel::kError, "view_failed", {{"doc", documentId_}, {"error", moved.message()}});
    }
  }
}

void TileStreams::applyDue(TileCache& tiles, Clock::time_point now, Clock::duration interval,
                           uint64_t version) {
  dropGone();
  std::vector<Stream*> candidates;
  for (auto& [session, s] : streams_) {
    if (s.pending && (s.continuing || now >= s.lastApplied + interval)) candidates.push_back(&s);
  }
  // The longest waiting first, at most kViewsPerTurn of them: the rest go
  // in the next turn, after the edits that came meanwhile.
  std::sort(candidates.begin(), candidates.end(),
            [](const Stream* a, const Stream* b) { return a->lastApplied < b->lastApplied; });
  if (candidates.size() > kViewsPerTurn) candidates.resize(kViewsPerTurn);
  std::vector<Stream*> due;
  for (Stream* stream : candidates) {
    Stream& s = *stream;
    s.view = *s.pending;
    s.viewSeq = s.pendingSeq;
    s.pending.reset();
    // The interval between a subscriber's views counts from its last new
    // one: a continuation is the server's, not the client's, and a view the
    // client sends meanwhile still waits its interval.
    if (!s.continuing) {
      s.lastApplied = now;
      ++stats_.viewsApplied;
    }
    s.continuing = false;
    due.push_back(&s);
  }
  moveEach(tiles, due, version, version, 0, 0, /*announce=*/true, kNewTilesPerTurn);
  continueIncomplete(due);
}

void TileStreams::continueIncomplete(const std::vector<Stream*>& moved) {
  // A view the allowance held back goes on in a later turn, due at once,
  // unless a newer one came meanwhile (which waits for its interval).
  for (Stream* s : moved) {
    if (s->complete || s->pending) continue;
    s->pending = s->view;
    s->pendingSeq = s->viewSeq;
    s->continuing = true;
    ++stats_.viewContinuations;
  }
}

void TileStreams::afterEdit(TileCache& tiles, std::span<const TileKey> reached, uint64_t fromVersion,
                            uint64_t toVersion, uint64_t authorSession, uint64_t editId) {
  dropGone();
  if (cacheReplaced_) {
    // Every held tile is stale: every stream chooses again, now.
    cacheReplaced_ = false;
    unsettledTiles_.clear();
    std::vector<Stream*> all;
    for (auto& [session, s] : streams_) all.push_back(&s);
    moveEach(tiles, all, fromVersion, toVersion, authorSession, editId, false);
    return;
  }
  // Every stream gets the held tiles the edits reached, again, at once:
  // building their meshes and encoding them is all an edit waits for. A
  // stream whose camera's walk read one of them (showed it, or refined it)
  // may choose otherwise under its new bounds; measuring them is left to
  // settle, and its delta is not complete meanwhile. A walk whose budget
  // raised the tolerance read more (each raised tolerance walks again): it
  // always chooses again. (Tiles' triangle counts do not change with edits,
  // so a selection within its budget stays within it.)
  for (auto& [session, s] : streams_) {
    bool read = s.toleranceRaised;
    for (const TileKey& key : reached) {
      if (auto held = s.held.find(key); held != s.held.end()) {
        held->second.stale = true;
        read = true;
      } else if (std::binary_search(s.refined.begin(), s.refined.end(), key)) {
        read = true;
      }
    }
    if (read) {
      s.unsettled = true;
    } else if (!s.unsettled) {
      ++stats_.viewsUnchangedByEdits;
    }
    if (Status sent = resendStale(tiles, s, reached, fromVersion, toVersion, authorSession, editId);
        !sent.isOk()) {
      logEvent(LogLevel::kError, "view_failed", {{"doc", documentId_}, {"error", sent.message()}});
    }
  }
  unsettledTiles_.insert(reached.begin(), reached.end());
}

bool TileStreams::unsettled() const {
  for (const auto& [session, s] : streams_)
    if (s.unsettled) return true;
  return false;
}

bool TileStreams::settle(TileCache& tiles, uint64_t version) {
  dropGone();
  // Measuring the reached tiles that waiting streams read is most of the
  // work: one tile at a time, so that an edit that comes meanwhile waits
  // for one tile, not for all of them.
  auto readByAWaitingStream = [&](const TileKey& key) {
    for (const auto& [session, s] : streams_) {
      if (s.unsettled && !s.pending && !s.toleranceRaised &&
          (s.held.count(key) || std::binary_search(s.refined.begin(), s.refined.end(), key)))
        return true;
    }
    return false;
  };
  bool measuredAny = false;
  for (const TileKey& key : unsettledTiles_) {
    if (tiles.hasBounds(key) || !readByAWaitingStream(key)) continue;
    if (measuredAny && editsWait_ && editsWait_()) return false;
    (void)tiles.bounds(key);  // on an error, keepsSelection fails below and the stream moves
    measuredAny = true;
  }
  const std::vector<TileKey> reached(unsettledTiles_.begin(), unsettledTiles_.end());
  unsettledTiles_.clear();
  std::vector<Stream*> moving;
  for (auto& [session, s] : streams_) {
    if (!s.unsettled || s.pending) continue;  // a waiting camera chooses again anyway
    auto keeps = s.toleranceRaised ? Expected<bool>(false) : keepsSelection(tiles, s, reached);
    if (!keeps.isOk() || !*keeps) {
      moving.push_back(&s);
      continue;
    }
    s.unsettled = false;
    ++stats_.viewsUnchangedByEdits;
    DeltaContent done = deltaFor(s, version, version, 0, 0);
    done.surfaceHash = s.surfaceHash;
    done.viewComplete = s.complete;
    send(s, std::move(done));
  }
  moveEach(tiles, moving, version, version, 0, 0, /*announce=*/true, kNewTilesPerTurn);
  continueIncomplete(moving);
  return true;
}

Expected<bool> TileStreams::keepsSelection(TileCache& tiles, const Stream& s,
                                           std::span<const TileKey> reached) {
  for (const TileKey& key : reached) {
    const bool shown = s.held.count(key) != 0;
    const bool refined = !shown && std::binary_search(s.refined.begin(), s.refined.end(), key);
    if (!shown && !refined) continue;  // the walk did not read it
    TESSERA_ASSIGN_OR_RETURN(TileBounds bounds, tiles.bounds(key));
    const bool refines = tiles.tree().hasChildren(key) &&
                         refinesTile(judgeTile(s.view, key, bounds), bounds, s.view.tolerancePixels);
    if (refines != refined) return false;
  }
  return true;
}

Status TileStreams::resendStale(TileCache& tiles, Stream& s, std::span<const TileKey> reached,
                                uint64_t fromVersion, uint64_t toVersion, uint64_t authorSession,
                                uint64_t editId) {
  Chunks c{deltaFor(s, fromVersion, toVersion, authorSession, editId)};
  for (const TileKey& key : reached) {
    auto found = s.held.find(key);
    if (found == s.held.end() || !found->second.stale) continue;
    TESSERA_RETURN_IF_ERROR(putTile(tiles, s, key, c));
    sendIfFull(s, c);
  }
  c.delta.surfaceHash = s.surfaceHash;
  c.delta.viewComplete = s.complete && !s.unsettled;
  send(s, std::move(c.delta));
  return Status::ok();
}

Status TileStreams::putTile(TileCache& tiles, Stream& s, const TileKey& key, Chunks& c) {
  TESSERA_ASSIGN_OR_RETURN(EncodedTile tile, tiles.encoded(key, c.delta.toVersion));
  auto [held, added] = s.held.try_emplace(key);
  if (!added) s.surfaceHash -= held->second.hash;
  held->second = {tile.hash, false};
  s.surfaceHash += tile.hash;
  c.delta.regions.push_back({key.regionId(), tile.bytes, true});
  c.bytes += tile.bytes->size();
  return Status::ok();
}

void TileStreams::sendIfFull(Stream& s, Chunks& c) {
  if (c.bytes < kChunkBytes) return;
  DeltaContent next =
      deltaFor(s, c.delta.toVersion, c.delta.toVersion, c.delta.authorSession, c.delta.editId);
  c.delta.surfaceHash = s.surfaceHash;
  send(s, std::exchange(c.delta, std::move(next)));
  c.sentAny = true;
  c.bytes = 0;
}

void TileStreams::forgetAllTiles() {
  for (auto& [session, s] : streams_) {
    for (auto& [key, held] : s.held) held.stale = true;
  }
  cacheReplaced_ = true;
}

Status TileStreams::moveTo(TileCache& tiles, Stream& s, const TileSelection& target, uint64_t fromVersion,
                           uint64_t toVersion, uint64_t authorSession, uint64_t editId, bool announce) {
  const TileTree& tree = tiles.tree();
  // Sorted vectors, not sets: a camera turn moves a stream of hundreds of
  // tiles, most of them held already, and this is its bookkeeping.
  std::vector<TileKey> wanted;
  wanted.reserve(target.tiles.size());
  for (const SelectedTile& t : target.tiles) wanted.push_back(t.key);
  std::sort(wanted.begin(), wanted.end());
  auto isWanted = [&](const TileKey& k) { return std::binary_search(wanted.begin(), wanted.end(), k); };
  auto fresh = [&](const TileKey& k) {
    auto it = s.held.find(k);
    return it != s.held.end() && !it->second.stale;
  };
  // The held tiles that are not wanted, in key order (both are sorted).
  std::vector<TileKey> leaving;
  {
    auto w = wanted.begin();
    for (const auto& [key, held] : s.held) {
      while (w != wanted.end() && *w < key) ++w;
      if (w == wanted.end() || *w != key) leaving.push_back(key);
    }
  }
  // The walk read the same tiles as before if it shows the same ones.
  const bool sameTiles = leaving.empty() && wanted.size() == s.held.size();
  // A held tile that is not wanted waits for the wanted tiles over it (an
  // ancestor) or under it (descendants) that it does not hold fresh yet.
  std::map<TileKey, int> waiting;
  for (const TileKey& key : leaving) waiting[key] = 0;
  std::map<TileKey, std::vector<TileKey>> waiters;
  auto depend = [&](const TileKey& waiter, const TileKey& want) {
    if (fresh(want)) return;
    ++waiting[waiter];
    waiters[want].push_back(waiter);
  };
  for (const TileKey& key : leaving) {
    for (TileKey a = key; a.level > 0;) {
      a = tree.parent(a);
      if (isWanted(a)) depend(key, a);
    }
  }
  if (!leaving.empty()) {
    for (const TileKey& want : wanted) {
      for (TileKey a = want; a.level > 0;) {
        a = tree.parent(a);
        if (std::binary_search(leaving.begin(), leaving.end(), a)) depend(a, want);
      }
    }
  }
  // The preview, shown alone while held, waits for the visible tiles only
  // (they come first): the picture then changes once, to the view's.
  if (waiting.count(TileKey::preview())) {
    for (const SelectedTile& t : target.tiles)
      if (t.visible) depend(TileKey::preview(), t.key);
  }

  Chunks c{deltaFor(s, fromVersion, toVersion, authorSession, editId)};
  auto drop = [&](const TileKey& key) {
    auto held = s.held.find(key);
    if (held == s.held.end()) return;
    s.surfaceHash -= held->second.hash;
    s.held.erase(held);
    c.delta.removed.push_back(key.regionId());
  };
  for (const auto& [leaving, count] : waiting)
    if (count == 0) drop(leaving);
  for (const SelectedTile& t : target.tiles) {
    if (fresh(t.key)) continue;
    TESSERA_RETURN_IF_ERROR(putTile(tiles, s, t.key, c));
    if (auto w = waiters.find(t.key); w != waiters.end()) {
      for (const TileKey& leaving : w->second)
        if (--waiting[leaving] == 0) drop(leaving);
    }
    sendIfFull(s, c);
  }
  // Nothing should be left waiting: the wanted tiles cover the surface.
  for (const auto& [leaving, count] : waiting)
    if (count > 0) drop(leaving);
  if (!sameTiles) {
    std::vector<TileKey> refined;
    for (const SelectedTile& t : target.tiles) {
      for (TileKey a = t.key; a.level > 0;) refined.push_back(a = tree.parent(a));
    }
    std::sort(refined.begin(), refined.end());
    refined.erase(std::unique(refined.begin(), refined.end()), refined.end());
    s.refined = std::move(refined);
  }
  s.toleranceRaised = target.tolerancePixels > s.view.tolerancePixels;
  s.complete = target.complete;
  s.unsettled = false;  // chosen at the tiles' current bounds
  // The last delta says the view is complete; a move that changed nothing
  // sends none, but a new subscription and an edit always end with one.
  if (!c.delta.regions.empty() || !c.delta.removed.empty() || c.sentAny || fromVersion != toVersion ||
      announce) {
    c.delta.surfaceHash = s.surfaceHash;
    c.delta.viewComplete = s.complete;
    send(s, std::move(c.delta));
  }
  return Status::ok();
}

DeltaContent TileStreams::deltaFor(const Stream& s, uint64_t fromVersion, uint64_t toVersion,
                                   uint64_t authorSession, uint64_t editId) const {
  DeltaContent d;
  d.documentId = documentId_;
  d.viewSeq = s.viewSeq;
  d.fromVersion = fromVersion;
  d.toVersion = toVersion;
  d.authorSession = authorSession;
  d.editId = editId;
  return d;
}

void TileStreams::send(Stream& s, DeltaContent delta) {
  auto who = s.who.lock();
  if (!who) return;
  auto content = std::make_shared<const DeltaContent>(std::move(delta));
  auto frame = encodeDeltaFrame(*content, maxFrameBytes_);
  if (!frame) {
    logEvent(LogLevel::kError, "tile_delta_too_large", {{"doc", documentId_}});
    return;
  }
  who->send({frame, content});
}

}  // namespace tessera::server
