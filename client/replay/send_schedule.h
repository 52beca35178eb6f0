// When an editor of a load run sends (docs/REPLAY.md §3.3 "An open
// model"): times fixed before the run, from its start, whatever the
// server or the tester does meanwhile, so that a send that goes out late
// is counted late and its latency counts from when it was due, as wrk2
// and k6's arrival-rate executors count (coordinated omission: Tene,
// "How NOT to Measure Latency"). Constant spacing, or Poisson arrivals
// (exponential gaps of the same mean) from a seed.
#pragma once

#include <chrono>
#include <cstdint>
#include <random>
#include <string>

#include "core/util/status.h"

namespace tessera::replay {

enum class Arrivals { kConstant, kPoisson };

// "constant" or "poisson".
Expected<Arrivals> parseArrivals(const std::string& name);
const char* arrivalsName(Arrivals arrivals);

class SendSchedule {
 public:
  using Clock = std::chrono::steady_clock;

  // `ratePerSecond` > 0. Constant: due at start + (k + phase) / rate, phase
  // in [0, 1) (editors spread over one period). Poisson: the first gap and
  // every later one drawn from `seed`.
  SendSchedule(Arrivals arrivals, double ratePerSecond, Clock::time_point start, double phase, uint64_t seed);

  // The next send's due time, and the step past it.
  Clock::time_point due() const { return due_; }
  void advance();

 private:
  Clock::duration gap();

  Arrivals arrivals_;
  double rate_;
  Clock::time_point start_, due_;
  int64_t index_ = 0;
  double phase_;
  std::mt19937_64 rng_;
};

}  // namespace tessera::replay
