// The report of a load run (docs/REPLAY.md §3.1): what runLoad measured,
// turned into the versioned JSON report and the summary for people.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "client/replay/load.h"
#include "client/replay/load_state.h"
#include "client/replay/proc_sample.h"
#include "client/replay/server_window.h"

namespace tessera::replay {

// What one run leaves besides `Shared`'s counters.
struct LoadRunData {
  Clock::time_point begin{};
  bool started = false;  // editing started (not stopped while connecting)
  Clock::time_point start{}, editsDone{};
  double connectMs = 0, settleMs = 0;
  int decodingViewers = 0, threadedViewers = 0, poolThreads = 0;
  std::vector<ViewerResult> viewers;
  ProcSample cpuBefore, cpuAfter;
  double testerCpuBefore = 0, testerCpuAfter = 0;  // this process's CPU seconds over the editing
  // Per second of editing: the tester's CPU percent, and the server's when sampled.
  struct CpuSecond {
    double tester = 0;
    std::optional<double> server;
  };
  std::vector<CpuSecond> cpuPerSecond;
  int64_t rssPeak = 0;
  std::optional<ServerStatsSample> statsStart, statsEnd;
  std::string statsError;  // why there is no window
};

// The latency samples the report summarizes (milliseconds, warm-up left out).
struct LoadLatencies {
  std::vector<double> toAck, toDelta, toTiles;
};

// Reads `shared` after every connection thread has ended; the samples go
// to `latencies` when given.
nlohmann::json buildLoadReport(const LoadOptions& options, Shared& shared, const LoadRunData& run,
                               LoadLatencies* latencies = nullptr);

// This process's CPU time so far, user and system, in seconds.
double processCpuSeconds();

// The "latency_ms" entry of some samples (milliseconds): count, mean, stddev,
// min, p50, p90, p95, p99, p99_9, max, to the microsecond.
nlohmann::json latencyJson(const std::vector<double>& samples);

}  // namespace tessera::replay
