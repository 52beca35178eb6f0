// The q-quantile of timing samples (nearest rank), 0 when there are none:
// the p50/p99 counters of the benchmarks that time each operation.
#pragma once

#include <algorithm>
#include <vector>

namespace tessera::bench {

inline double percentile(std::vector<double> samples, double q) {
  if (samples.empty()) return 0.0;
  std::sort(samples.begin(), samples.end());
  return samples[std::min(samples.size() - 1, static_cast<size_t>(q * static_cast<double>(samples.size())))];
}

}  // namespace tessera::bench
