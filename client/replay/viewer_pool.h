// Counting viewers for load runs (docs/REPLAY.md §3), many per thread: each
// connects, says hello, opens the document, subscribes and then only
// counts what arrives (bytes, version continuity, delta arrival times),
// without decoding. A thread per connection cannot hold a thousand viewers
// on a 2-core machine beside the server it measures; one Asio io_context
// with a strand per viewer can.
#pragma once

#include <span>

#include "client/replay/load.h"
#include "client/replay/load_state.h"

namespace tessera::replay {

struct ViewerPoolOptions {
  int firstIndex = 0;   // viewers are named viewer-<firstIndex + i + 1>
  int threads = 1;      // threads running the pool's io_context
  int maxJoining = 32;  // viewers connecting and subscribing at once
};

// Runs `results.size()` viewers until the run ends (shared.stopViewing, then
// every viewer at the last acked version or `drainSeconds` later), the
// run's stop (shared.stopped) or `hardDeadline`. Blocks the calling thread; errors go to `shared`.
void runViewerPool(const LoadOptions& options, const ViewerPoolOptions& pool, Clock::time_point hardDeadline,
                   Shared& shared, std::span<ViewerResult> results);

}  // namespace tessera::replay
