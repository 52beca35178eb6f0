// The latency histogram of a load report (docs/REPLAY.md §3.1): HDR-style
// log-linear buckets over whole microseconds, fixed for every run so that
// reports can be added up and compared bucket by bucket.
//
// Layout: a sample of v microseconds (floor, negative as 0) falls in
//   [v, v + 1)                                  for v < 8,
//   [(8 + s) * 2^(k-3), (9 + s) * 2^(k-3))      for 2^k <= v < 2^(k+1), k >= 3,
// where s = floor(v / 2^(k-3)) - 8 in 0..7: every power of two is cut into
// 8 equal buckets, so a bucket is at most 1/8 (12.5 %) of its lower bound
// wide. All bucket edges are integers.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

namespace tessera::replay {

struct HistogramBucket {
  uint64_t lowerMicros = 0;  // inclusive
  uint64_t upperMicros = 0;  // exclusive
  uint64_t count = 0;
};

// The bucket holding `micros` (count 0).
HistogramBucket bucketOf(uint64_t micros);

class LatencyHistogram {
 public:
  void addMilliseconds(double ms);
  void addMicros(uint64_t micros);
  uint64_t total() const { return total_; }
  // The non-empty buckets, in increasing order.
  std::vector<HistogramBucket> buckets() const;

 private:
  std::map<uint64_t, uint64_t> counts_;  // lower bound -> count
  uint64_t total_ = 0;
};

}  // namespace tessera::replay
