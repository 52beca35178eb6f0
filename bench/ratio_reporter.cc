#include "bench/ratio_reporter.h"

#include <cstdio>

namespace tessera::bench {

void RatioReporter::ReportRuns(const std::vector<Run>& runs) {
  ConsoleReporter::ReportRuns(runs);
  for (const auto& run : runs) {
    if (run.error_occurred) continue;
    // One iteration run, or the median when repetitions are aggregated.
    const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
    if (run.run_type != Run::RT_Iteration && !median) continue;
    // Adjusted time is in the run's display unit; normalise to nanoseconds.
    double ns = run.GetAdjustedRealTime() * 1e9 / benchmark::GetTimeUnitMultiplier(run.time_unit);
    realTimeNs_[run.run_name.str()] = ns;
  }
}

int RatioReporter::printRatios() const {
  int pairs = 0;
  std::printf("\n%-34s %14s %14s %8s\n", "benchmark", "Tessera ms", "OpenSubdiv ms", "ratio");
  for (const auto& [name, ns] : realTimeNs_) {
    auto at = name.find("/Tessera");
    if (at == std::string::npos) continue;
    std::string reference = name.substr(0, at) + "/OpenSubdiv" + name.substr(at + 8);
    auto it = realTimeNs_.find(reference);
    if (it == realTimeNs_.end()) continue;
    std::string label = name.substr(0, at) + name.substr(at + 8);
    std::printf("%-34s %14.3f %14.3f %8.3f\n", label.c_str(), ns / 1e6, it->second / 1e6, ns / it->second);
    ++pairs;
  }
  std::printf("ratio = Tessera time / OpenSubdiv time (<= 1.0 means Tessera is as fast or faster)\n");
  return pairs;
}

int runWithRatios(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.printRatios();
  benchmark::Shutdown();
  return 0;
}

}  // namespace tessera::bench
