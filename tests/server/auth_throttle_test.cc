// Failed authentications space an address's attempts (docs/PROTOCOL.md §4.1):
// doubling delays up to a cap, queued turns for parallel attempts, no effect
// on other addresses, and failures forgotten after the window.
#include <gtest/gtest.h>

#include "server/net/auth_throttle.h"

namespace tessera::server {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

TEST(AuthThrottle, DelaysDoublePerFailureUpToTheCapForThatAddressOnly) {
  AuthThrottle throttle(
      {.baseDelay = milliseconds(100), .maxDelay = milliseconds(350), .forgetAfter = seconds(60)});
  const auto t0 = AuthThrottle::Clock::time_point{} + seconds(1000);
  EXPECT_EQ(throttle.admit("10.0.0.1", t0), t0);  // no failure yet: at once
  EXPECT_EQ(throttle.failed("10.0.0.1", t0), 1);
  // The next attempt waits 100 ms; after a second failure 200, then the cap.
  auto turn = throttle.admit("10.0.0.1", t0);
  EXPECT_EQ(turn, t0 + milliseconds(100));
  EXPECT_EQ(throttle.failed("10.0.0.1", turn), 2);
  auto next = throttle.admit("10.0.0.1", turn);
  EXPECT_EQ(next, turn + milliseconds(200));
  EXPECT_EQ(throttle.failed("10.0.0.1", next), 3);
  EXPECT_EQ(throttle.admit("10.0.0.1", next), next + milliseconds(350));
  // Another address is never delayed.
  EXPECT_EQ(throttle.admit("10.0.0.2", t0), t0);
}

TEST(AuthThrottle, ParallelAttemptsQueueBehindEachOther) {
  AuthThrottle throttle(
      {.baseDelay = milliseconds(100), .maxDelay = seconds(10), .forgetAfter = seconds(60)});
  const auto t0 = AuthThrottle::Clock::time_point{} + seconds(1000);
  throttle.failed("a", t0);
  // Three connections arrive at once: each gets its own turn, 100 ms apart
  // (the failures so far earn 100 ms each).
  const auto first = throttle.admit("a", t0);
  const auto second = throttle.admit("a", t0);
  const auto third = throttle.admit("a", t0);
  EXPECT_EQ(first, t0 + milliseconds(100));
  EXPECT_EQ(second, t0 + milliseconds(200));
  EXPECT_EQ(third, t0 + milliseconds(300));
}

TEST(AuthThrottle, FailuresAreForgottenAfterTheWindow) {
  AuthThrottle throttle(
      {.baseDelay = milliseconds(100), .maxDelay = seconds(10), .forgetAfter = seconds(60)});
  const auto t0 = AuthThrottle::Clock::time_point{} + seconds(1000);
  for (int i = 0; i < 5; ++i) throttle.failed("a", t0);
  const auto later = t0 + seconds(61);
  EXPECT_EQ(throttle.admit("a", later), later);
  EXPECT_EQ(throttle.failed("a", later), 1);
}

TEST(AuthThrottle, ManyAddressesArePrunedNotKeptForever) {
  AuthThrottle throttle({.baseDelay = milliseconds(1),
                         .maxDelay = milliseconds(2),
                         .forgetAfter = seconds(1),
                         .maxAddresses = 100});
  const auto t0 = AuthThrottle::Clock::time_point{} + seconds(1000);
  for (int i = 0; i < 1000; ++i) throttle.failed("addr-" + std::to_string(i), t0 + milliseconds(i));
  // The newest address still counts its failure; the oldest were dropped.
  EXPECT_EQ(throttle.failed("addr-999", t0 + milliseconds(1000)), 2);
  EXPECT_EQ(throttle.failed("addr-0", t0 + milliseconds(1000)), 1);
}

}  // namespace
}  // namespace tessera::server
