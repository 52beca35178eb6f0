// /metrics: the server's counters, gauges and latency histograms in the
// Prometheus text format (prometheus-cpp's serializer). Read from
// ServerStats and the store's stats at scrape time, so recording stays a
// few atomic operations on the hot paths. Names and meanings are listed in
// docs/OPERATIONS.md.
#pragma once

#include <chrono>
#include <deque>
#include <mutex>
#include <string>
#include <utility>

#include "server/base/server_stats.h"
#include "server/store/store.h"

namespace tessera::server {

// Edits per second over the last `window`, from samples of the edit counter
// (taken once a second by the endpoint and at every scrape).
class RateWindow {
 public:
  explicit RateWindow(std::chrono::seconds window) : window_(window) {}
  void sample(std::chrono::steady_clock::time_point now, int64_t total);
  double perSecond() const;

 private:
  std::chrono::seconds window_;
  mutable std::mutex mutex_;
  std::deque<std::pair<std::chrono::steady_clock::time_point, int64_t>> samples_;
};

// The whole /metrics body.
struct MetricsSample {
  const ServerStats& stats;
  store::StoreStats store;
  int64_t documentsOpen = 0;
  double editsPerSecond = 0;
  store::Durability durability;
};
std::string renderMetrics(const MetricsSample& sample);

}  // namespace tessera::server
