// Failed authentications slow down per address (docs/PROTOCOL.md §4.1). Attempts
// from one address are evaluated one after another, spaced by a delay that
// doubles with each recent failure (from `baseDelay` up to `maxDelay`), so
// a guesser gets a handful of tries a minute instead of thousands a second,
// however many connections it opens. Other addresses are never delayed:
// the right token from elsewhere is served at once. Failures older than
// `forgetAfter` no longer count. Thread-safe; memory is bounded by pruning
// the addresses whose failures were forgotten.
#pragma once

#include <chrono>
#include <cstddef>
#include <map>
#include <mutex>
#include <string>

namespace tessera::server {

struct AuthThrottleOptions {
  std::chrono::milliseconds baseDelay{250};
  std::chrono::milliseconds maxDelay{30'000};
  std::chrono::seconds forgetAfter{600};
  size_t maxAddresses = 100'000;  // pruned beyond this
};

class AuthThrottle {
 public:
  using Clock = std::chrono::steady_clock;
  explicit AuthThrottle(AuthThrottleOptions options = {}) : options_(options) {}

  // When an authentication attempt from `address` that arrives `now` may
  // be evaluated: now, unless recent failures from that address are still
  // spacing its attempts. Reserves that turn.
  Clock::time_point admit(const std::string& address, Clock::time_point now);
  // Records a failed attempt; returns the address's recent failures.
  int failed(const std::string& address, Clock::time_point now);

 private:
  struct Record {
    int failures = 0;
    Clock::time_point lastFailure{};
    Clock::time_point nextTurn{};  // the earliest time the next attempt is evaluated
  };
  Clock::duration delayFor(int failures) const;
  void forgetStale(Record& record, Clock::time_point now) const;
  void prune(Clock::time_point now);

  const AuthThrottleOptions options_;
  std::mutex mutex_;
  std::map<std::string, Record> addresses_;
};

}  // namespace tessera::server
