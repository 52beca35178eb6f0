// Summary statistics of a load run's latency samples (docs/REPLAY.md §3.1):
// mean, standard deviation, nearest-rank percentiles and the extremes, as
// wrk and k6 report them, computed from every raw sample (no histogram
// interpolation), so that a threshold sees exactly what the report says.
#pragma once

#include <cstddef>
#include <vector>

namespace tessera::replay {

struct LatencySummary {
  size_t count = 0;
  double mean = 0;
  double stddev = 0;  // sample standard deviation (n - 1), as wrk's; 0 for one sample
  double min = 0;
  double p50 = 0, p90 = 0, p95 = 0, p99 = 0, p999 = 0;
  double max = 0;
};

// The nearest-rank percentile of sorted samples: the smallest sample with
// at least p % of the samples at or below it (p in (0, 100]). Empty input
// gives 0.
double nearestRank(const std::vector<double>& sorted, double percent);

// Sorts `samples` (taken by value) and summarizes them.
LatencySummary summarizeLatencies(std::vector<double> samples);

}  // namespace tessera::replay
