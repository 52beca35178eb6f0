// Admission and memory of a document's work (docs/ARCHITECTURE.md, "Bulk work"): which lane a
// task takes, the triangle estimates a request is judged by before any
// work, and freeing views and documents off the interactive workers. Part
// of DocumentHost.
#include <malloc.h>
#include <boost/asio/post.hpp>

#include <algorithm>

#include "server/base/log.h"
#include "server/document/document_host.h"

namespace tessera::server {

void DocumentHost::leaveOtherViews(uint64_t session, const std::string& key) {
  // One profile per subscriber and document: the new one replaces the old,
  // only once the new one exists (a refused profile keeps the old one).
  for (auto& [other, view] : views_) {
    if (other != key) view.subscribers.erase(session), view.knownVersion.erase(session);
  }
  dropUnwatchedViews();
}

namespace {

bool watched(const auto& view) {
  return std::any_of(view.subscribers.begin(), view.subscribers.end(),
                     [](const auto& s) { return !s.second.expired(); });
}

}  // namespace

void DocumentHost::dropUnwatchedViews() {
  // The unwatched morph views, most recently used first: kept while their
  // triangles fit the budget of one subscriber (--max-triangles).
  std::vector<std::pair<uint64_t, std::string>> morphs;
  for (const auto& [key, view] : views_) {
    if (view.morphT && !watched(view)) morphs.emplace_back(view.lastUsed, key);
  }
  std::sort(morphs.rbegin(), morphs.rend());
  std::set<std::string> kept;
  int64_t triangles = 0;
  for (const auto& [used, key] : morphs) {
    triangles += views_.at(key).tessellation->numTriangles();
    if (triangles > config_.limits.maxTrianglesPerSubscriber) break;
    kept.insert(key);
  }
  auto dropped = std::make_shared<Released>();
  for (auto it = views_.begin(); it != views_.end();) {
    if (watched(it->second) || kept.count(it->first)) {
      ++it;
      continue;
    }
    logEvent(LogLevel::kDebug, "profile_dropped", {{"doc", id_.value}, {"profile", it->first}});
    dropped->views.insert(views_.extract(it++));
  }
  if (!dropped->views.empty()) releaseOnBulk(std::move(dropped));
}

void DocumentHost::dropRetainedMorphViews() {
  auto dropped = std::make_shared<Released>();
  for (auto it = views_.begin(); it != views_.end();) {
    if (!it->second.morphT || watched(it->second)) {
      ++it;
      continue;
    }
    dropped->views.insert(views_.extract(it++));
  }
  if (!dropped->views.empty()) releaseOnBulk(std::move(dropped));
}

// Memory a large view or document held is freed on a bulk thread (a
// tessellation of millions of triangles takes seconds to free), then given
// back to the system (malloc_trim walks the heap).
void DocumentHost::releaseOnBulk(std::shared_ptr<Released> released) {
  boost::asio::post(bulk_, [released = std::move(released)]() mutable {
    released.reset();
    ::malloc_trim(0);
  });
}

void DocumentHost::trimMemory() {
  boost::asio::post(bulk_, [] { ::malloc_trim(0); });
}

Lane DocumentHost::laneFor(int64_t triangles) const {
  return triangles > config_.bulkTriangles ? Lane::kBulk : Lane::kInteractive;
}

int64_t DocumentHost::uniformTriangles(uint32_t level) const {
  if (level > static_cast<uint32_t>(counts_.maxLevel())) {
    // Beyond the counts: four times per level, saturating.
    int64_t t = static_cast<int64_t>(counts_.faces(counts_.maxLevel()));
    for (uint32_t l = static_cast<uint32_t>(counts_.maxLevel()); l < level && t < (INT64_MAX >> 2); ++l)
      t *= 4;
    return t;
  }
  return static_cast<int64_t>(counts_.faces(static_cast<int>(level)));
}

int64_t DocumentHost::minimumTriangles(const wire::LodProfile& profile) const {
  return uniformTriangles(std::min<uint32_t>(profile.base_level(), 64));
}

int64_t DocumentHost::maximumTriangles(const wire::LodProfile& profile) const {
  const int64_t budget =
      profile.triangle_budget() == 0
          ? config_.limits.maxTrianglesPerSubscriber
          : static_cast<int64_t>(std::min<uint64_t>(
                profile.triangle_budget(), static_cast<uint64_t>(config_.limits.maxTrianglesPerSubscriber)));
  return std::min(budget, uniformTriangles(std::min<uint32_t>(profile.max_level(), 64)));
}

}  // namespace tessera::server
