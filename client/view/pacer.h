// Pacer: a token bucket in front of the connection, as client/web's Pacer.
// The server refuses commands beyond its own bucket (200 a second in bursts
// of 200 by default, docs/PROTOCOL.md section 9), and undoing a long drag
// sends one Undo per edit (docs/VIEWER.md, "Undo and redo"), so tessera-view
// sends at most kRate commands a second, in bursts of kBurst.
//
// Not thread-safe: the Connection's network thread alone uses it.
#pragma once

#include <chrono>

namespace tessera::view {

class Pacer {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr double kRate = 150, kBurst = 150;

  // Full: `burst` commands may go at once.
  explicit Pacer(Clock::time_point now, double rate = kRate, double burst = kBurst);

  // Adds the tokens earned since the last refill (`rate` a second), up to `burst`.
  void refill(Clock::time_point now);
  // True, spending a token, when one more command may go now.
  bool take();

  double tokens() const { return tokens_; }

 private:
  double rate_, burst_;
  double tokens_;
  Clock::time_point at_;
};

}  // namespace tessera::view
