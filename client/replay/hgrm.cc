#include "client/replay/hgrm.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "client/replay/latency_stats.h"

namespace tessera::replay {

std::string percentileDistribution(std::vector<double> samples) {
  std::sort(samples.begin(), samples.end());
  std::string out = "       Value     Percentile TotalCount 1/(1-Percentile)\n\n";
  char line[160];
  const size_t n = samples.size();
  if (n > 0) {
    // Percentile ticks: 5 per halving of the distance to 100 %, as
    // HdrHistogram's default (ticksPerHalfDistance = 5), until the last
    // sample; then the 100 % row.
    double percentile = 0;
    for (int halving = 0;; ++halving) {
      const double remaining = std::ldexp(100.0, -halving);  // 100, 50, 25, ...
      const double step = remaining / 2 / 5;
      bool done = false;
      for (int tick = 0; tick < 5 && !done; ++tick) {
        const double at = percentile + tick * step;
        const size_t rank = std::max<size_t>(1, static_cast<size_t>(std::ceil(at / 100 * n)));
        const double value = samples[std::min(rank, n) - 1];
        std::snprintf(line, sizeof line, "%12.3f %1.12f %10zu %14.2f\n", value, at / 100, std::min(rank, n),
                      1 / (1 - at / 100));
        out += line;
        done = rank >= n;
      }
      percentile += remaining / 2;
      if (done || percentile >= 100 || halving > 40) break;
    }
    std::snprintf(line, sizeof line, "%12.3f %1.12f %10zu %14s\n", samples.back(), 1.0, n, "inf");
    out += line;
  }
  const LatencySummary s = summarizeLatencies(samples);
  std::snprintf(line, sizeof line, "#[Mean    = %12.3f, StdDeviation   = %12.3f]\n", s.mean, s.stddev);
  out += line;
  std::snprintf(line, sizeof line, "#[Max     = %12.3f, Total count    = %12zu]\n", s.max, n);
  out += line;
  return out;
}

}  // namespace tessera::replay
