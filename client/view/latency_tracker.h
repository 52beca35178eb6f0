// LatencyTracker: tessera-view's edit-to-delta latency (docs/VIEWER.md, "Undo
// and redo", last paragraph), as client/web's LatencyTracker: the time from
// sending an edit (or an Undo or Redo) to receiving the delta that reaches
// the version its Ack names. A delta covers from_version < v <= to_version
// (a merged delta spans several versions), and it can arrive before the Ack
// (docs/PROTOCOL.md 6.1: merging can move it ahead), so the arrivals of this
// session's own deltas are remembered too, the newest kKeep of them.
//
// Not thread-safe: the Connection's network thread alone uses it, and
// copies summary() into its stats under its mutex.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>

namespace tessera::view {

class LatencyTracker {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr size_t kKeep = 256;

  struct Summary {
    double lastMs = -1;  // -1 before the first sample
    double maxMs = 0;
    uint64_t samples = 0;
  };

  // An edit's Ack: the `version` it made, `sentAt` when the edit went out;
  // `viewVersion` is the version the view shows already. Measured at once
  // when the view has the version and one of this session's deltas reaching
  // it was remembered (the earliest such); otherwise, when the view lacks the
  // version, the Ack waits for its delta.
  void acked(uint64_t version, Clock::time_point sentAt, uint64_t viewVersion);
  // A delta from..to applied to the view at `at`; `own` when this session
  // authored it. It measures every waiting Ack it reaches; an own delta that
  // reaches none is remembered.
  void delta(uint64_t fromVersion, uint64_t toVersion, bool own, Clock::time_point at);
  // After a reconnection nothing in flight will be answered.
  void reset();

  // Acks whose delta has not arrived yet.
  size_t awaitingDelta() const { return acked_.size(); }
  const Summary& summary() const { return summary_; }

 private:
  void record(Clock::duration d);

  // Versions acked but whose delta has not arrived, and the reverse (by
  // the delta's to_version).
  std::map<uint64_t, Clock::time_point> acked_, arrivals_;
  Summary summary_;
};

}  // namespace tessera::view
