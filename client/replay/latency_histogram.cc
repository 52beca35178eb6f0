#include "client/replay/latency_histogram.h"

#include <bit>
#include <cmath>

namespace tessera::replay {

namespace {
constexpr int kSubBucketBits = 3;  // 8 buckets per power of two
constexpr uint64_t kLinearBelow = uint64_t{1} << kSubBucketBits;
}  // namespace

HistogramBucket bucketOf(uint64_t micros) {
  if (micros < kLinearBelow) return {micros, micros + 1, 0};
  const int k = std::bit_width(micros) - 1;  // 2^k <= micros < 2^(k+1)
  const int shift = k - kSubBucketBits;
  const uint64_t lower = (micros >> shift) << shift;
  return {lower, lower + (uint64_t{1} << shift), 0};
}

void LatencyHistogram::addMilliseconds(double ms) {
  // NaN and negative (clock skew cannot happen on steady_clock, but a caller
  // may pass anything) count as 0; the cap keeps the cast defined.
  double micros = std::floor(ms * 1000.0);
  if (!(micros > 0)) micros = 0;
  addMicros(micros >= 1.8e19 ? uint64_t{1} << 63 : static_cast<uint64_t>(micros));
}

void LatencyHistogram::addMicros(uint64_t micros) {
  ++counts_[bucketOf(micros).lowerMicros];
  ++total_;
}

std::vector<HistogramBucket> LatencyHistogram::buckets() const {
  std::vector<HistogramBucket> out;
  out.reserve(counts_.size());
  for (const auto& [lower, count] : counts_) {
    HistogramBucket b = bucketOf(lower);
    b.count = count;
    out.push_back(b);
  }
  return out;
}

}  // namespace tessera::replay
