#include "client/view/latency_tracker.h"

#include <algorithm>

namespace tessera::view {

void LatencyTracker::acked(uint64_t version, Clock::time_point sentAt, uint64_t viewVersion) {
  // The first delta reaching the version (deltas may be merged).
  auto arrived = arrivals_.lower_bound(version);
  if (arrived != arrivals_.end() && version <= viewVersion) {
    record(arrived->second - sentAt);
    arrivals_.erase(arrived);
  } else if (version > viewVersion) {
    acked_[version] = sentAt;
  }
}

void LatencyTracker::delta(uint64_t fromVersion, uint64_t toVersion, bool own, Clock::time_point at) {
  // An acked version inside this delta's range, else remember the arrival.
  bool matched = false;
  for (auto it = acked_.upper_bound(fromVersion); it != acked_.end() && it->first <= toVersion;) {
    record(at - it->second);
    it = acked_.erase(it);
    matched = true;
  }
  if (!matched && own) arrivals_[toVersion] = at;
  while (arrivals_.size() > kKeep) arrivals_.erase(arrivals_.begin());
}

void LatencyTracker::reset() {
  acked_.clear();
  arrivals_.clear();
}

void LatencyTracker::record(Clock::duration d) {
  const double ms = std::chrono::duration<double, std::milli>(d).count();
  summary_.lastMs = ms;
  summary_.maxMs = std::max(summary_.maxMs, ms);
  ++summary_.samples;
}

}  // namespace tessera::view
