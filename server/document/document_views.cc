#include "server/document/document_views.h"

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

#include "server/base/log.h"
#include "server/document/replies.h"

namespace tessera::server {

namespace {

// Whether a live subscriber other than `except` (0: none excepted) watches it.
bool watched(const LodView& view, uint64_t except = 0) {
  return std::any_of(view.subscribers.begin(), view.subscribers.end(),
                     [&](const auto& s) { return s.first != except && !s.second.expired(); });
}

}  // namespace

DocumentViews::DocumentViews(store::DocumentId document, int64_t retainedMorphTriangles,
                             uint32_t maxFrameBytes)
    : document_(document), retainedMorphTriangles_(retainedMorphTriangles), maxFrameBytes_(maxFrameBytes) {}

LodView* DocumentViews::find(const std::string& key) {
  auto it = views_.find(key);
  return it == views_.end() ? nullptr : &it->second;
}

size_t DocumentViews::watchedByOthers(uint64_t session) const {
  size_t kept = 0;
  for (const auto& [key, view] : views_) kept += watched(view, session) ? 1 : 0;
  return kept;
}

size_t DocumentViews::subscriberCount() const {
  size_t subscribers = 0;
  for (const auto& [key, view] : views_) subscribers += view.subscribers.size();
  return subscribers;
}

LodView& DocumentViews::add(const std::string& key, LodView view) {
  return views_.emplace(key, std::move(view)).first->second;
}

void DocumentViews::attach(LodView& view, const std::shared_ptr<Subscriber>& who, uint64_t version,
                           RegionCodec codec) {
  view.subscribers[who->sessionId()] = who;
  view.knownVersion[who->sessionId()] = version;
  view.codecOf[who->sessionId()] = codec;
  view.lastUsed = ++useClock_;
}

DocumentViews::Views DocumentViews::leaveAllBut(uint64_t session, const std::string& key) {
  return forget(session, key);
}

DocumentViews::Views DocumentViews::leave(uint64_t session) {
  return forget(session, {});
}

DocumentViews::Views DocumentViews::forget(uint64_t session, std::string_view keep) {
  for (auto& [key, view] : views_) {
    if (key != keep)
      view.subscribers.erase(session), view.knownVersion.erase(session), view.codecOf.erase(session);
  }
  return dropUnwatched(keep);
}

DocumentViews::Views DocumentViews::dropUnwatched(std::string_view keep) {
  // The unwatched morph views, most recently used first: kept while their
  // triangles fit the budget. `keep` is about to be watched: neither dropped
  // nor counted.
  std::vector<std::pair<uint64_t, std::string>> morphs;
  for (const auto& [key, view] : views_) {
    if (view.morphT && !watched(view) && key != keep) morphs.emplace_back(view.lastUsed, key);
  }
  std::sort(morphs.rbegin(), morphs.rend());
  std::set<std::string> kept;
  int64_t triangles = 0;
  for (const auto& [used, key] : morphs) {
    triangles += views_.at(key).tessellation->numTriangles();
    if (triangles > retainedMorphTriangles_) break;
    kept.insert(key);
  }
  Views dropped;
  for (auto it = views_.begin(); it != views_.end();) {
    if (watched(it->second) || kept.count(it->first) || it->first == keep) {
      ++it;
      continue;
    }
    logEvent(LogLevel::kDebug, "profile_dropped", {{"doc", document_.value}, {"profile", it->first}});
    dropped.insert(views_.extract(it++));
  }
  return dropped;
}

DocumentViews::Views DocumentViews::dropRetainedMorphViews() {
  Views dropped;
  for (auto it = views_.begin(); it != views_.end();) {
    if (!it->second.morphT || watched(it->second)) {
      ++it;
      continue;
    }
    dropped.insert(views_.extract(it++));
  }
  return dropped;
}

void DocumentViews::updateEach(const std::function<Status(const std::string& key, LodView& view)>& update) {
  for (auto it = views_.begin(); it != views_.end();) {
    Status updated = update(it->first, it->second);
    if (updated.isOk()) {
      ++it;
      continue;
    }
    wire::ServerMessage error;
    error.mutable_error()->set_code(wire::ERROR_CODE_INTERNAL);
    error.mutable_error()->set_message("LOD profile " + it->first + " dropped: " + updated.message());
    auto frame = frameOf(error, maxFrameBytes_);
    for (auto& [session, weak] : it->second.subscribers) {
      if (auto who = weak.lock()) who->send({frame, nullptr});
    }
    it = views_.erase(it);
  }
}

void DocumentViews::send(FlushBatch& batch) {
  for (auto& [key, view] : views_) {
    for (auto& [session, weak] : view.subscribers) {
      if (view.knownVersion[session] >= batch.toVersion) continue;  // its snapshot holds this one
      // The delta in the subscriber's codec (lod_view.h deltaKey).
      const auto codec = view.codecOf.find(session);
      const std::string frameKey =
          deltaKey(key, codec == view.codecOf.end() ? RegionCodec::kDraco : codec->second);
      auto frame = batch.frames.find(frameKey);
      if (frame == batch.frames.end() || !frame->second) continue;
      if (auto who = weak.lock()) who->send({frame->second, batch.deltas[frameKey]});
    }
  }
  batch.frames.clear();  // the batch stays only to order the recorders' commands
  batch.deltas.clear();
}

DocumentViews::Views DocumentViews::takeAll() {
  return std::exchange(views_, {});
}

}  // namespace tessera::server
