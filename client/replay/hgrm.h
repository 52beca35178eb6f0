// Latency samples in HdrHistogram's percentile distribution format
// (`.hgrm`, as HdrHistogram's outputPercentileDistribution prints it and
// its plotter and wrk2 read it): "Value Percentile TotalCount
// 1/(1-Percentile)" rows at percentiles that halve the distance to 100 %
// in 5 ticks each, then the mean, deviation, maximum and count. Values are
// milliseconds. Computed from the raw samples (nearest rank), not from a
// bucketed histogram, so the rows are the samples themselves.
#pragma once

#include <string>
#include <vector>

namespace tessera::replay {

std::string percentileDistribution(std::vector<double> samplesMs);

}  // namespace tessera::replay
