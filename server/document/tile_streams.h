// The view-dependent subscribers of one document (docs/VIEWS.md "The
// server", docs/PROTOCOL.md "Views"): each one's camera, the tiles it
// holds, and the messages that move what it holds to what its camera
// needs. A new subscriber gets the coarsest tiles as a snapshot (a whole
// picture at once), then the rest as deltas in the selection's order:
// visible before hidden, coarse before fine, near before far. A tile it
// holds goes once every tile that replaces it has arrived, so the surface
// it shows never has a hole. Each payload comes from the document's
// TileCache, encoded once for everyone; only the frames are per
// subscriber, since their tile sets differ.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <vector>

#include "core/view/view.h"
#include "protocol/tessera.pb.h"
#include "server/base/server_stats.h"
#include "server/document/delta.h"
#include "server/document/subscriber.h"
#include "server/document/tile_cache.h"

namespace tessera::server {

class TileStreams {
 public:
  using Clock = std::chrono::steady_clock;

  // `editsWait`, if given, says whether an edit of the document waits
  // (to be applied, committed or flushed) behind the running turn: a turn
  // of camera moves or settling then builds no further tiles, and its views
  // go on after the edit (docs/VIEWS.md "The server").
  TileStreams(uint64_t documentId, uint32_t maxFrameBytes, ServerStats& stats,
              std::function<bool()> editsWait = {})
      : documentId_(documentId),
        maxFrameBytes_(maxFrameBytes),
        stats_(stats),
        editsWait_(std::move(editsWait)) {}
  ~TileStreams();

  // `who` watches the document through `view`, within `budget`, from
  // `version`, the document's, every tile current: its first picture goes
  // now, one snapshot (the preview, or the roots where the document has no
  // preview), and its previous stream, if any, goes. `profile` is echoed
  // in the snapshot. `preview` is the preview at `version` where the caller
  // has asked the cache for it already, so that one viewer is one cache
  // lookup. Errors: a tile that cannot be encoded.
  Status open(TileCache& tiles, const std::shared_ptr<Subscriber>& who, const View& view, int64_t budget,
              const wire::LodProfile& profile, uint64_t version, bool resync,
              std::optional<EncodedTile> preview = std::nullopt);
  // Then the tiles its camera needs, `target`, as deltas in the
  // selection's order, at `version` still. Errors: a stream not opened, a
  // tile that cannot be encoded.
  Status start(TileCache& tiles, uint64_t session, const TileSelection& target, uint64_t version);
  bool has(uint64_t session) const { return streams_.count(session) > 0; }
  size_t size() const { return streams_.size(); }
  void leave(uint64_t session);

  // A new camera for `session`'s stream (SetView `clientSeq`), applied by
  // applyDue once its interval has passed; a newer one replaces it meanwhile.
  void setPending(uint64_t session, const View& view, uint64_t clientSeq);
  // When the earliest waiting view is due, if one waits.
  std::optional<Clock::time_point> nextDue(Clock::duration interval) const;
  // Applies the waiting views that are due at `now`, the longest waiting
  // first and a few per call (the caller calls again while nextDue says
  // one is due, letting other work in between): the tiles that changed
  // go to its subscriber as deltas at `version`, the last naming the
  // SetView (even when nothing changed: the client learns its view was
  // applied). A call builds at most kNewTilesPerTurn tiles: a view that
  // needs more gets a coarser picture now, its last delta not complete, and
  // waits again, due at once, for the next call to go on.
  void applyDue(TileCache& tiles, Clock::time_point now, Clock::duration interval, uint64_t version);

  // After edits from `fromVersion` to `toVersion` (the cache has forgotten
  // the tiles `reached`): every stream gets the tiles it holds that changed,
  // at once. A stream whose camera's walk read a reached tile may need
  // other tiles now: its delta is not complete, and settle decides.
  void afterEdit(TileCache& tiles, std::span<const TileKey> reached, uint64_t fromVersion, uint64_t toVersion,
                 uint64_t authorSession, uint64_t editId);
  // Whether some stream waits for settle.
  bool unsettled() const;
  // Measures the tiles the edits since the last call reached, and moves
  // each stream waiting for it to what its camera needs now, at `version`
  // (as applyDue: at most kNewTilesPerTurn new tiles, the rest in later
  // turns); a stream whose choice stays gets an empty complete delta
  // (docs/VIEWS.md "The server"). False: it stopped measuring because an
  // edit waits (editsWait), and must be called again.
  bool settle(TileCache& tiles, uint64_t version);
  // The cache was replaced (the document's keys changed): every held tile
  // is sent again.
  void forgetAllTiles();

 private:
  struct Held {
    uint64_t hash = 0;
    bool stale = false;  // an edit reached it after it was sent
  };
  struct Stream {
    std::weak_ptr<Subscriber> who;
    View view;
    int64_t budget = 0;
    std::map<TileKey, Held> held;
    // The ancestors of the tiles it selected last, sorted: with those, every
    // tile its camera's walk read (tile_selection.h).
    std::vector<TileKey> refined;
    // Its budget raised the tolerance (tile_selection.h): the walk read more.
    bool toleranceRaised = false;
    // Its last selection was whole; not when a turn's allowance of new
    // tiles held some back (its view then waits to go on, `continuing`).
    bool complete = true, continuing = false;
    // An edit reached a tile its walk read since it last chose: settle
    // decides whether it keeps its choice.
    bool unsettled = false;
    uint64_t surfaceHash = 0;  // the sum of held tiles' hashes (PROTOCOL 6.5)
    std::optional<View> pending;
    uint64_t pendingSeq = 0, viewSeq = 0;  // SetView client_seqs: waiting, and the view applied
    Clock::time_point lastApplied{};
  };
  // Moves `s` to `target`: deltas of at most about kChunkBytes of tiles,
  // the first from `fromVersion`, all to `toVersion`, the last marked
  // complete. `announce`: send that last one even if nothing changed.
  Status moveTo(TileCache& tiles, Stream& s, const TileSelection& target, uint64_t fromVersion,
                uint64_t toVersion, uint64_t authorSession, uint64_t editId, bool announce = false);
  void send(Stream& s, DeltaContent delta);
  // One move's deltas, cut at about kChunkBytes of tiles: the first from the
  // move's first version, the others from its last.
  struct Chunks {
    DeltaContent delta;
    size_t bytes = 0;
    bool sentAny = false;
  };
  // Puts `key`'s tile, encoded at the delta's version, into the current
  // delta as what `s` holds under `key` from now on.
  Status putTile(TileCache& tiles, Stream& s, const TileKey& key, Chunks& c);
  // Sends the current delta once it holds kChunkBytes of tiles, and starts
  // the next.
  void sendIfFull(Stream& s, Chunks& c);
  // An empty delta of `s`'s stream (its view_seq) between these versions.
  DeltaContent deltaFor(const Stream& s, uint64_t fromVersion, uint64_t toVersion, uint64_t authorSession,
                        uint64_t editId) const;
  // Whether the edits that reached `reached` leave `s`'s choice of tiles as
  // it was: every reached tile its walk read keeps its decision under its
  // new bounds (it stays refined, or stays shown).
  Expected<bool> keepsSelection(TileCache& tiles, const Stream& s, std::span<const TileKey> reached);
  // Sends `s` its held tiles that the edits reached (`reached`), again, in
  // deltas from `fromVersion` to `toVersion`, the last complete.
  Status resendStale(TileCache& tiles, Stream& s, std::span<const TileKey> reached, uint64_t fromVersion,
                     uint64_t toVersion, uint64_t authorSession, uint64_t editId);
  // Chooses again for every stream of `moving` in one walk (building at
  // most `newTiles` tiles if that is >= 0), then moves each.
  void moveEach(TileCache& tiles, const std::vector<Stream*>& moving, uint64_t fromVersion,
                uint64_t toVersion, uint64_t authorSession, uint64_t editId, bool announce,
                int64_t newTiles = -1);
  // Makes the views of `moved` the allowance left incomplete wait again,
  // due at once.
  void continueIncomplete(const std::vector<Stream*>& moved);
  // Forgets the streams whose subscriber is gone.
  void dropGone();

  const uint64_t documentId_;
  const uint32_t maxFrameBytes_;
  ServerStats& stats_;
  const std::function<bool()> editsWait_;
  std::map<uint64_t, Stream> streams_;  // by session
  // forgetAllTiles since the last afterEdit: every held tile is stale, not
  // only those an edit reached, so every stream chooses again.
  bool cacheReplaced_ = false;
  // The tiles edits reached since the last settle.
  std::set<TileKey> unsettledTiles_;
};

}  // namespace tessera::server
