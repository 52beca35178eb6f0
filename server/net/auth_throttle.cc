#include "server/net/auth_throttle.h"

#include <algorithm>
#include <vector>

namespace tessera::server {

AuthThrottle::Clock::duration AuthThrottle::delayFor(int failures) const {
  if (failures <= 0) return Clock::duration::zero();
  // base * 2^(failures - 1), capped; the shift stays small so it cannot overflow.
  const auto doubled = options_.baseDelay * (int64_t{1} << std::min(failures - 1, 20));
  return std::min<Clock::duration>(doubled, options_.maxDelay);
}

void AuthThrottle::forgetStale(Record& record, Clock::time_point now) const {
  if (record.failures > 0 && now - record.lastFailure > options_.forgetAfter) record.failures = 0;
}

AuthThrottle::Clock::time_point AuthThrottle::admit(const std::string& address, Clock::time_point now) {
  std::lock_guard lock(mutex_);
  auto it = addresses_.find(address);
  if (it == addresses_.end()) return now;  // never failed: no bookkeeping at all
  Record& record = it->second;
  forgetStale(record, now);
  const Clock::time_point turn = std::max(now, record.nextTurn);
  // The attempt after this one waits for this one's turn plus the delay the
  // failures so far earn, so parallel connections queue up behind each other.
  record.nextTurn = turn + delayFor(record.failures);
  return turn;
}

int AuthThrottle::failed(const std::string& address, Clock::time_point now) {
  std::lock_guard lock(mutex_);
  if (addresses_.size() >= options_.maxAddresses) prune(now);
  Record& record = addresses_[address];
  forgetStale(record, now);
  ++record.failures;
  record.lastFailure = now;
  record.nextTurn = std::max(record.nextTurn, now + delayFor(record.failures));
  return record.failures;
}

void AuthThrottle::prune(Clock::time_point now) {
  for (auto it = addresses_.begin(); it != addresses_.end();) {
    const bool stale = now - it->second.lastFailure > options_.forgetAfter && it->second.nextTurn <= now;
    it = stale ? addresses_.erase(it) : std::next(it);
  }
  // Still full (a flood of fresh addresses): forget the oldest tenth rather
  // than grow; the per-address and total connection limits still hold.
  if (addresses_.size() < options_.maxAddresses) return;
  std::vector<std::pair<Clock::time_point, std::string>> byAge;
  byAge.reserve(addresses_.size());
  for (const auto& [address, record] : addresses_) byAge.emplace_back(record.lastFailure, address);
  const size_t drop = addresses_.size() - options_.maxAddresses * 9 / 10;
  std::nth_element(byAge.begin(), byAge.begin() + static_cast<std::ptrdiff_t>(drop), byAge.end());
  for (size_t i = 0; i < drop; ++i) addresses_.erase(byAge[i].second);
}

}  // namespace tessera::server
