#include "client/replay/send_schedule.h"

namespace tessera::replay {

Expected<Arrivals> parseArrivals(const std::string& name) {
  if (name == "constant") return Arrivals::kConstant;
  if (name == "poisson") return Arrivals::kPoisson;
  return invalidArgument("--arrivals: expects constant or poisson, got '" + name + "'");
}

const char* arrivalsName(Arrivals arrivals) {
  return arrivals == Arrivals::kPoisson ? "poisson" : "constant";
}

SendSchedule::SendSchedule(Arrivals arrivals, double ratePerSecond, Clock::time_point start, double phase,
                           uint64_t seed)
    : arrivals_(arrivals), rate_(ratePerSecond), start_(start), phase_(phase), rng_(seed) {
  due_ = arrivals_ == Arrivals::kConstant
             ? start_ + std::chrono::round<Clock::duration>(std::chrono::duration<double>(phase_ / rate_))
             : start_ + gap();
}

SendSchedule::Clock::duration SendSchedule::gap() {
  std::exponential_distribution<double> exponential(rate_);
  return std::chrono::round<Clock::duration>(std::chrono::duration<double>(exponential(rng_)));
}

void SendSchedule::advance() {
  ++index_;
  if (arrivals_ == Arrivals::kPoisson) {
    due_ += gap();
    return;
  }
  // From the start each time, so that rounding never accumulates.
  due_ = start_ + std::chrono::round<Clock::duration>(
                      std::chrono::duration<double>((static_cast<double>(index_) + phase_) / rate_));
}

}  // namespace tessera::replay
