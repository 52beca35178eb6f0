#include "client/replay/load_series.h"

#include <algorithm>
#include <cmath>

#include "client/replay/latency_stats.h"

namespace tessera::replay {

namespace {

double round3(double x) {
  return std::round(x * 1000) / 1000;
}

nlohmann::json brief(const std::vector<double>& samples) {
  const LatencySummary s = summarizeLatencies(samples);
  nlohmann::json j = {{"count", s.count}};
  if (s.count == 0) return j;
  j["mean"] = round3(s.mean);
  j["p50"] = round3(s.p50);
  j["p99"] = round3(s.p99);
  j["max"] = round3(s.max);
  return j;
}

}  // namespace

size_t LoadSeries::indexOf(double seconds) const {
  if (seconds_ == 0 || !(seconds > 0)) return 0;
  return std::min(seconds_ - 1, static_cast<size_t>(std::floor(std::min(seconds, 1e9))));
}

LoadSeries::Second& LoadSeries::at(size_t index) {
  if (data_.size() < seconds_) data_.resize(seconds_);
  return data_[index];
}

void LoadSeries::sent(size_t second, int64_t count) {
  if (seconds_ > 0) at(std::min(second, seconds_ - 1)).sent += count;
}
void LoadSeries::acked(double sentSeconds, double ms) {
  if (seconds_ > 0) at(indexOf(sentSeconds)).ack.push_back(ms);
}
void LoadSeries::delta(double sentSeconds, double ms) {
  if (seconds_ > 0) at(indexOf(sentSeconds)).delta.push_back(ms);
}
void LoadSeries::rejected(double sentSeconds) {
  if (seconds_ > 0) ++at(indexOf(sentSeconds)).rejected;
}
void LoadSeries::error(double atSeconds) {
  if (seconds_ > 0) ++at(indexOf(atSeconds)).errors;
}
void LoadSeries::cpu(size_t second, double testerPercent, std::optional<double> serverPercent) {
  if (second >= seconds_) return;
  Second& s = at(second);
  s.testerCpu = round3(testerPercent);
  if (serverPercent) s.serverCpu = round3(*serverPercent);
}

nlohmann::json LoadSeries::toJson() const {
  nlohmann::json out = nlohmann::json::array();
  for (size_t i = 0; i < seconds_; ++i) {
    static const Second kEmpty;
    const Second& s = i < data_.size() ? data_[i] : kEmpty;
    out.push_back({{"second", i},
                   {"sent", s.sent},
                   {"acked", s.ack.size()},
                   {"rejected", s.rejected},
                   {"errors", s.errors},
                   {"edit_to_ack", brief(s.ack)},
                   {"edit_to_delta", brief(s.delta)}});
    if (s.testerCpu) out.back()["tester_cpu_percent"] = *s.testerCpu;
    if (s.serverCpu) out.back()["server_cpu_percent"] = *s.serverCpu;
  }
  return out;
}

}  // namespace tessera::replay
