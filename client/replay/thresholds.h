// Pass/fail thresholds on a load report (docs/REPLAY.md §3.2), as k6 users
// gate releases on them: `--threshold 'p99<50ms' --threshold 'errors=0'`.
//
//   THRESHOLD := [LATENCY "."] STAT OP VALUE UNIT  |  COUNT OP VALUE
//   LATENCY   := ack | edit_to_ack | delta | edit_to_delta   (default: edit_to_delta)
//   STAT      := mean | stddev | min | max | p50 | p90 | p95 | p99 | p99.9
//   UNIT      := us | ms | s
//   COUNT     := errors | rejected | gaps | resyncs | behind | sent | acked | throughput
//   OP        := < | <= | > | >= | = | ==
// Spaces are ignored. A threshold is checked against the report's values
// (latencies in ms to the microsecond), so what it prints is what the report
// holds.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/util/status.h"

namespace tessera::replay {

enum class Comparison { kLess, kLessEqual, kGreater, kGreaterEqual, kEqual };

struct Threshold {
  std::string text;    // as given
  std::string metric;  // "edit_to_ack", "edit_to_delta", or "" for a count
  std::string stat;    // the report's key: "p99", "p99_9", "mean", ... or the count's name
  Comparison op = Comparison::kLess;
  double limit = 0;  // milliseconds for latencies
};

// An error names the threshold and what is wrong with it.
Expected<Threshold> parseThreshold(const std::string& text);

struct ThresholdResult {
  Threshold threshold;
  bool passed = false;
  bool measured = false;         // false: nothing to compare (a latency without samples): failed
  double value = 0;              // in ms for latencies
  std::string describe() const;  // "p99<50ms: edit_to_delta p99 63.204 ms (failed)"
};

std::vector<ThresholdResult> checkThresholds(const std::vector<Threshold>& thresholds,
                                             const nlohmann::json& report);

}  // namespace tessera::replay
