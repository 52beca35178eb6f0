// A console reporter that also remembers each benchmark's real time, so that
// main() can print Tessera / OpenSubdiv ratios for benchmarks named
// "<group>/Tessera/<arg>" and "<group>/OpenSubdiv/<arg>".
#pragma once

#include <map>
#include <string>

#include <benchmark/benchmark.h>

namespace tessera::bench {

class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override;
  // Prints one line per pair found; returns the number of pairs.
  int printRatios() const;

 private:
  std::map<std::string, double> realTimeNs_;
};

// Runs the registered benchmarks with a RatioReporter (Google Benchmark's
// flags from argv), prints the ratios, and returns main()'s exit code.
int runWithRatios(int argc, char** argv);

}  // namespace tessera::bench
