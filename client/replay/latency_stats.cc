#include "client/replay/latency_stats.h"

#include <algorithm>
#include <cmath>

namespace tessera::replay {

double nearestRank(const std::vector<double>& sorted, double percent) {
  if (sorted.empty()) return 0;
  // ceil(p/100 * n), shrunk by a relative 1e-12 first so that exact ranks
  // stay exact: 99.9 is not a binary fraction, and 99.9 * 1000 / 100 comes
  // out a hair above 999, which would make the p99.9 of 1000 samples their
  // maximum. The rounding error is ~1e-16 relative; a true fraction of a
  // rank is far larger than 1e-12 relative for any sample count we hold.
  const double n = static_cast<double>(sorted.size());
  double rank = std::ceil(percent * n / 100.0 * (1 - 1e-12));
  rank = std::clamp(rank, 1.0, n);
  return sorted[static_cast<size_t>(rank) - 1];
}

LatencySummary summarizeLatencies(std::vector<double> samples) {
  LatencySummary s;
  s.count = samples.size();
  if (samples.empty()) return s;
  std::sort(samples.begin(), samples.end());
  // Two passes (mean, then squared deviations): a single-pass sum of squares
  // loses precision when the spread is small against the mean.
  double sum = 0;
  for (double x : samples) sum += x;
  s.mean = sum / static_cast<double>(s.count);
  if (s.count > 1) {
    double squares = 0;
    for (double x : samples) squares += (x - s.mean) * (x - s.mean);
    s.stddev = std::sqrt(squares / static_cast<double>(s.count - 1));
  }
  s.min = samples.front();
  s.max = samples.back();
  s.p50 = nearestRank(samples, 50);
  s.p90 = nearestRank(samples, 90);
  s.p95 = nearestRank(samples, 95);
  s.p99 = nearestRank(samples, 99);
  s.p999 = nearestRank(samples, 99.9);
  return s;
}

}  // namespace tessera::replay
