// Server-wide counters for the stats command and logs. Atomics: updated
// from document strands and connection strands alike.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>

#include "server/base/latency_histogram.h"

namespace tessera::server {

struct ServerStats {
  std::atomic<int64_t> connections{0};
  std::atomic<int64_t> connectionsTotal{0};
  std::atomic<int64_t> edits{0};
  std::atomic<int64_t> rejects{0};
  std::atomic<int64_t> bytesSent{0};
  std::atomic<int64_t> framesSent{0};
  std::atomic<int64_t> deltaMerges{0};
  std::atomic<int64_t> resyncs{0};
  std::atomic<int64_t> queueBytes{0};     // sum over clients
  std::atomic<int64_t> queueBytesMax{0};  // largest single client queue seen
  std::atomic<int64_t> tessellateMicros{0};
  std::atomic<int64_t> encodeMicros{0};
  std::atomic<int64_t> commitMicros{0};  // apply to durable, summed
  std::atomic<int64_t> regionsEncoded{0};
  std::atomic<int64_t> deltaRegions{0};           // region payloads queued in deltas
  std::atomic<int64_t> deltaRegionsLayoutIds{0};  // of those, moved regions sent without their layout's ids
  std::atomic<int64_t> deltaFlushes{0};  // deltas made per view; a flush covers every edit queued together
  std::atomic<int64_t> connectionsRefused{0};  // over a connection limit, before any Hello
  std::atomic<int64_t> authFailures{0};        // Hellos with a token the store does not know
  // Cluster mode (docs/CLUSTER.md): this node's number, the documents whose lease
  // it holds, the documents it moved to another owner (or took over), and
  // the cluster messages it dropped as malformed.
  std::atomic<int64_t> clusterNode{0};
  std::atomic<int64_t> documentsOwned{0};
  std::atomic<int64_t> documentsMoved{0};
  std::atomic<int64_t> clusterMessagesDropped{0};
  std::atomic<int64_t> remoteSessions{0};  // other nodes' sessions served by this node's documents
  // View-dependent subscriptions (docs/VIEWS.md "The server"): tiles
  // tessellated (and built again after their mesh was released), encoded,
  // found encoded, evicted; encoded bytes held over every document; views
  // received and applied (the rest were replaced by newer ones in their
  // interval); subscribers with a view now.
  std::atomic<int64_t> tilesBuilt{0};
  std::atomic<int64_t> tilesEncoded{0};
  std::atomic<int64_t> tileCacheHits{0};
  std::atomic<int64_t> tileCacheEvictions{0};
  std::atomic<int64_t> tileCacheBytes{0};
  std::atomic<int64_t> viewsReceived{0};
  std::atomic<int64_t> viewsApplied{0};
  // View subscribers an edit reached no tile of: sent the new version
  // without choosing their tiles again.
  std::atomic<int64_t> viewsUnchangedByEdits{0};
  // Turns that went on with a view a turn's allowance of new tiles had left
  // incomplete (server/document/tile_streams.h).
  std::atomic<int64_t> viewContinuations{0};
  std::atomic<int64_t> viewSubscribers{0};
  // Latencies (histograms for /metrics): an edit from being applied to its
  // durable ack (the journal commit), a view's tessellation build or
  // update, and one region's encoding.
  LatencyHistogram ackLatency;
  LatencyHistogram tessellateLatency;
  LatencyHistogram encodeLatency;
  const std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();

  double uptimeSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  }
};

}  // namespace tessera::server
