// What the connections of one load run share (load.cc, viewer_pool.cc):
// counters every connection adds to, and each viewer's own results, merged
// into the report at the end.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <semaphore>
#include <string>
#include <unordered_map>
#include <vector>

#include "client/replay/delta_peek.h"
#include "protocol/tessera.pb.h"

namespace tessera::replay {

using Clock = std::chrono::steady_clock;

// One latency sample, with when its edit was sent (seconds since the start
// of editing), for the per-second series.
struct TimedSample {
  double sentSeconds = 0;
  double ms = 0;
};

// Counters every connection thread adds to; the rest is merged at the end.
struct Shared {
  std::atomic<bool> stopViewing{false};
  std::atomic<int64_t> sent{0}, acked{0}, rejected{0}, errors{0}, gaps{0}, resyncs{0}, deltas{0},
      viewersReady{0}, viewersDone{0};
  // Sends due before the end of editing that never went out (send_schedule.h).
  std::atomic<int64_t> dropped{0};
  std::atomic<uint64_t> maxAckedVersion{0};
  // Editors connect and open first, then wait for the start: joins make
  // Presence messages to every participant, and the edits should not queue
  // behind them.
  std::atomic<int64_t> editorsReady{0};
  std::atomic<bool> startEditing{false};
  std::atomic<int64_t> startNs{0};         // steady_clock, set before startEditing
  std::atomic<int64_t> lastPresenceNs{0};  // the latest Presence any viewer received
  // Viewers joining at once: connecting, subscribing and reading the snapshot.
  std::counting_semaphore<1024> joining{32};
  // The run cannot go on (a missing document, a refused token): every
  // connection leaves at once, without waiting for the drain.
  std::atomic<bool> stopped{false};
  std::mutex mu;  // guards what follows
  std::unordered_map<uint64_t, Clock::time_point> sendTimeOfVersion;
  std::vector<TimedSample> ackSamples;
  std::vector<double> rejectedAt;      // send times of rejected edits (seconds since the start)
  std::vector<int64_t> sentPerSecond;  // merged from every editor at its end
  std::vector<double> lateness;        // ms each send went out after it was due, merged likewise
  std::vector<Clock::time_point> errorTimes;
  std::vector<std::string> errorMessages;              // the first 20
  std::string stopReason;                              // the first reason given to stop()
  const Clock::time_point cameraEpoch = Clock::now();  // second 0 of every camera path
  Clock::time_point stoppedAt{};

  void error(const std::string& message) {
    ++errors;
    std::lock_guard lock(mu);
    errorTimes.push_back(Clock::now());
    if (errorMessages.size() < 20) errorMessages.push_back(message);
  }
  // Stops the run with `reason` (the first one is kept); also an error.
  void stop(const std::string& reason) {
    error(reason);
    std::lock_guard lock(mu);
    if (stopped.exchange(true)) return;
    stopReason = reason;
    stoppedAt = Clock::now();
  }
  double secondsSinceStart(Clock::time_point t) const {
    return std::chrono::duration<double>(t - Clock::time_point(Clock::duration(startNs.load()))).count();
  }
};

struct ViewerResult {
  bool ready = false;
  uint64_t version = 0;
  uint64_t hash = 0;  // decoding viewers only
  bool decoded = false;
  int64_t snapshotBytes = 0, deltaBytes = 0, presenceBytes = 0, presenceMessages = 0;
  struct DeltaArrival {
    uint64_t fromVersion, toVersion;
    Clock::time_point arrival;
    int64_t regions;
  };
  int64_t regionsReceived = 0;  // region payloads in deltas (tiles, for view-dependent viewers)
  std::vector<DeltaArrival> deltaTimes;
};

enum class ViewerEvent { kNone, kReady, kGap, kFatal };

// What a viewer makes of one server message, however it reads them (a
// thread per connection, or the pool): bytes, readiness, version
// continuity and delta arrivals. kGap: the viewer must subscribe again;
// kFatal: the server closed the connection with an error.
ViewerEvent trackViewerMessage(const wire::ServerMessage& m, Clock::time_point arrival, uint64_t document,
                               ViewerResult& out, Shared& shared);

// The same for a delta known by its header alone; `bytes` is its frame size.
ViewerEvent trackDelta(const DeltaHeader& d, int64_t bytes, Clock::time_point arrival, uint64_t document,
                       ViewerResult& out, Shared& shared);

struct LoadOptions;
// Viewer `viewer`'s Subscribe: the run's profile, or, with cameras, its
// camera now (the profile's triangle budget kept).
wire::ClientMessage subscribeMessage(const LoadOptions& o, int viewer, const Shared& shared);
// Its SetView now, if the run has cameras and one is due since `last`
// (updated then); nullopt otherwise.
std::optional<wire::ClientMessage> viewIfDue(const LoadOptions& o, int viewer, const Shared& shared,
                                             Clock::time_point& last);

}  // namespace tessera::replay
