// The per-second series of a load report (docs/REPLAY.md §3.1): for each
// second of editing, what was sent in it and how those edits fared. Events
// are placed by the send time of their edit, so an edit and every latency
// sample it caused fall in one second (an edit sent at 2.9 s whose delta
// arrived at 3.1 s counts in second 2); connection errors by the time they
// happened, those before the start in the first second and those after the
// last in the last.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

namespace tessera::replay {

class LoadSeries {
 public:
  explicit LoadSeries(size_t seconds) : seconds_(seconds) {}

  void sent(size_t second, int64_t count);
  void acked(double sentSeconds, double ms);
  void delta(double sentSeconds, double ms);
  void rejected(double sentSeconds);
  void error(double atSeconds);
  // The tester's CPU over that second, and the server's when sampled
  // (percent of one core), so that a late tester shows where it was late.
  void cpu(size_t second, double testerPercent, std::optional<double> serverPercent);

  // [{"second": 0, "sent": .., "acked": .., "rejected": .., "errors": ..,
  //   "edit_to_ack": {"count", "mean", "p50", "p99", "max"}, "edit_to_delta": {...},
  //   "tester_cpu_percent", "server_cpu_percent" (when sampled)}, ...]
  nlohmann::json toJson() const;

 private:
  struct Second {
    int64_t sent = 0, rejected = 0, errors = 0;
    std::vector<double> ack, delta;
    std::optional<double> testerCpu, serverCpu;
  };
  size_t indexOf(double seconds) const;
  Second& at(size_t index);

  size_t seconds_;
  std::vector<Second> data_;
};

}  // namespace tessera::replay
