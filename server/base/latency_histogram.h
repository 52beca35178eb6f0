// Latency histograms for the metrics endpoint (docs/OPERATIONS.md): fixed
// buckets, so recording is a few atomic increments on hot paths and a
// scrape reads them without locks. Bounds follow Prometheus' convention
// (upper bounds in seconds, "le"); they span 50 us to 10 s, the range from a
// small edit's ack to a large import.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>

namespace tessera::server {

inline constexpr std::array<double, 17> kLatencyBucketBounds = {
    0.00005, 0.0001, 0.00025, 0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 5, 10};

// Index of the first bucket whose bound is >= seconds; the last index (one
// past the bounds) is the overflow bucket (+Inf).
inline size_t latencyBucketIndex(double seconds) {
  size_t i = 0;
  while (i < kLatencyBucketBounds.size() && seconds > kLatencyBucketBounds[i]) ++i;
  return i;
}

// Microseconds from `start` to now, on the steady clock the server times
// its stages with.
inline int64_t microsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start)
      .count();
}

// A plain value: per-bucket (not cumulative) counts, count and sum.
struct LatencyBuckets {
  std::array<uint64_t, kLatencyBucketBounds.size() + 1> counts{};
  uint64_t count = 0;
  double sumSeconds = 0;

  void add(std::chrono::microseconds latency) {
    const double seconds = static_cast<double>(latency.count()) / 1e6;
    ++counts[latencyBucketIndex(seconds)];
    ++count;
    sumSeconds += seconds;
  }
};

// The same, recorded from many threads at once.
class LatencyHistogram {
 public:
  void add(std::chrono::microseconds latency) {
    const int64_t micros = latency.count() < 0 ? 0 : latency.count();
    counts_[latencyBucketIndex(static_cast<double>(micros) / 1e6)].fetch_add(1, std::memory_order_relaxed);
    sumMicros_.fetch_add(micros, std::memory_order_relaxed);
  }
  void addMicros(int64_t micros) { add(std::chrono::microseconds(micros)); }

  // Buckets read one by one: a scrape racing a record may see it in the
  // count but not yet in the sum, which Prometheus tolerates.
  LatencyBuckets snapshot() const {
    LatencyBuckets out;
    for (size_t i = 0; i < counts_.size(); ++i) {
      out.counts[i] = counts_[i].load(std::memory_order_relaxed);
      out.count += out.counts[i];
    }
    out.sumSeconds = static_cast<double>(sumMicros_.load(std::memory_order_relaxed)) / 1e6;
    return out;
  }

 private:
  std::array<std::atomic<uint64_t>, kLatencyBucketBounds.size() + 1> counts_{};
  std::atomic<int64_t> sumMicros_{0};
};

}  // namespace tessera::server
