// The views of one open document (docs/ARCHITECTURE.md, "One edit, end to
// end", steps 4 and 5, and "Bulk work"): a LodView per LOD profile asked, by
// the profile's key, and who watches each. A subscriber watches one view of
// a document, from the version its snapshot held (a delta that snapshot
// already holds is not sent to it); a view nobody watches is dropped, but
// for the most recently used morph views that fit one subscriber's budget
// (viewers playing a morph come back to the same times, and a kept view is
// not built and encoded again). It builds and encodes nothing (lod_view.h,
// morph_view.h) and runs on its host's strand; the views it drops go back
// to the host, which frees them off the interactive workers
// (bulk_release.h).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "core/util/status.h"
#include "server/document/commit_log.h"
#include "server/document/lod_view.h"
#include "server/document/subscriber.h"
#include "server/store/store.h"

namespace tessera::server {

class DocumentViews {
 public:
  using Views = std::map<std::string, LodView>;  // by LodProfile::key()

  // `retainedMorphTriangles`: the triangles of unwatched morph views kept
  // at most (--max-triangles, one subscriber's budget).
  DocumentViews(store::DocumentId document, int64_t retainedMorphTriangles, uint32_t maxFrameBytes);

  // The view of profile `key`, or null.
  LodView* find(const std::string& key);
  size_t size() const { return views_.size(); }
  // The views someone other than `session` watches: those left if `session`
  // moves to a view of its own.
  size_t watchedByOthers(uint64_t session) const;
  // Subscribers of every view (the flush's pacing).
  size_t subscriberCount() const;

  // Adds the view of profile `key` (not there yet).
  LodView& add(const std::string& key, LodView view);
  // `who` watches `view` from `version`, the version its snapshot holds,
  // in `codec`'s encodings.
  void attach(LodView& view, const std::shared_ptr<Subscriber>& who, uint64_t version,
              RegionCodec codec = RegionCodec::kDraco);
  // One profile per subscriber and document: `session` leaves every view but
  // `key`'s, once `key`'s exists (a refused profile keeps the old one);
  // then the unwatched views but `key`'s are dropped (dropUnwatched): the
  // view it moves to may be a retained morph view that the one it left
  // would otherwise push out of the budget.
  Views leaveAllBut(uint64_t session, const std::string& key);
  // `session` leaves every view; then the unwatched views are dropped.
  Views leave(uint64_t session);

  // Drops the views no subscriber watches, but the most recently used morph
  // views whose triangles fit `retainedMorphTriangles` and the view `keep`
  // (a subscriber is about to watch it); returns the dropped.
  Views dropUnwatched(std::string_view keep = {});
  // Drops every unwatched morph view (a key changed: they are stale);
  // returns them.
  Views dropRetainedMorphViews();

  // A flush: `update` on every view, in key order. A view whose update
  // fails is over its triangle budget now: its subscribers get an Error
  // naming the view and why, and the view goes (they may subscribe again
  // with another profile).
  void updateEach(const std::function<Status(const std::string& key, LodView& view)>& update);
  // Sends a flush's frames to the subscribers whose snapshot does not hold
  // them, then drops the frames: sending the batch again is a no-op.
  void send(FlushBatch& batch);

  // Every view, for the host to free when the document closes.
  Views takeAll();

 private:
  // `session` leaves every view but `keep`'s; then dropUnwatched(keep).
  Views forget(uint64_t session, std::string_view keep);
  const store::DocumentId document_;
  const int64_t retainedMorphTriangles_;
  const uint32_t maxFrameBytes_;
  Views views_;
  uint64_t useClock_ = 0;  // LodView::lastUsed: ticks when a subscriber joins a view
};

}  // namespace tessera::server
