#include "server/ops/metrics_exposition.h"

#include <prometheus/metric_family.h>
#include <prometheus/text_serializer.h>
#include <limits>
#include <vector>

#include "tessera/version.h"

namespace tessera::server {

void RateWindow::sample(std::chrono::steady_clock::time_point now, int64_t total) {
  std::lock_guard lock(mutex_);
  samples_.emplace_back(now, total);
  // Keep one sample at or before the window's start, so the rate spans it.
  while (samples_.size() > 2 && now - samples_[1].first >= window_) samples_.pop_front();
}

double RateWindow::perSecond() const {
  std::lock_guard lock(mutex_);
  if (samples_.size() < 2) return 0;
  const double seconds =
      std::chrono::duration<double>(samples_.back().first - samples_.front().first).count();
  return seconds > 0 ? static_cast<double>(samples_.back().second - samples_.front().second) / seconds : 0;
}

namespace {

using prometheus::ClientMetric;
using prometheus::MetricFamily;
using prometheus::MetricType;

MetricFamily scalar(std::string name, std::string help, MetricType type, double value) {
  ClientMetric metric;
  if (type == MetricType::Counter) {
    metric.counter.value = value;
  } else {
    metric.gauge.value = value;
  }
  return MetricFamily{std::move(name), std::move(help), type, {metric}};
}

MetricFamily counter(std::string name, std::string help, int64_t value) {
  return scalar(std::move(name), std::move(help), MetricType::Counter, static_cast<double>(value));
}

MetricFamily gauge(std::string name, std::string help, double value) {
  return scalar(std::move(name), std::move(help), MetricType::Gauge, value);
}

MetricFamily histogram(std::string name, std::string help, const LatencyBuckets& buckets) {
  ClientMetric metric;
  metric.histogram.sample_count = buckets.count;
  metric.histogram.sample_sum = buckets.sumSeconds;
  uint64_t cumulative = 0;
  for (size_t i = 0; i < buckets.counts.size(); ++i) {
    cumulative += buckets.counts[i];
    const double bound =
        i < kLatencyBucketBounds.size() ? kLatencyBucketBounds[i] : std::numeric_limits<double>::infinity();
    metric.histogram.bucket.push_back({cumulative, bound});
  }
  return MetricFamily{std::move(name), std::move(help), MetricType::Histogram, {metric}};
}

}  // namespace

std::string renderMetrics(const MetricsSample& sample) {
  const ServerStats& s = sample.stats;
  const store::StoreStats& store = sample.store;
  const double editsPerSecond = sample.editsPerSecond;
  ClientMetric info;
  info.label = {{"version", kVersion}};
  info.gauge.value = 1;
  ClientMetric durability;
  durability.label = {{"backend", sample.durability.backend},
                      {"engine_version", sample.durability.engineVersion},
                      {"write_sync", store::writeSyncName(sample.durability.sync)}};
  durability.gauge.value = 1;
  std::vector<MetricFamily> families = {
      MetricFamily{"tessera_build_info", "Always 1; the version is a label.", MetricType::Gauge, {info}},
      MetricFamily{
          "tessera_store_durability_info",
          "Always 1. write_sync: each-write (on disk before the acknowledgement), not-each-write "
          "(a majority's memory and page cache), or configured (per the NATS servers' sync_interval).",
          MetricType::Gauge,
          {durability}},
      gauge("tessera_uptime_seconds", "Seconds since the server started.", s.uptimeSeconds()),
      gauge("tessera_connections", "Open client connections.", static_cast<double>(s.connections.load())),
      counter("tessera_connections_total", "Connections accepted.", s.connectionsTotal.load()),
      counter("tessera_connections_refused_total", "Connections refused by a connection limit.",
              s.connectionsRefused.load()),
      counter("tessera_auth_failures_total", "Hellos with a token the store does not know.",
              s.authFailures.load()),
      gauge("tessera_documents_open", "Documents held in memory.", static_cast<double>(sample.documentsOpen)),
      counter("tessera_edits_total", "Edits applied (moves, sharpness, vertex types, undo, redo).",
              s.edits.load()),
      gauge("tessera_edits_per_second", "Edits per second over the last 10 s.", editsPerSecond),
      counter("tessera_refusals_total",
              "Commands refused with a Reject (limits, bad arguments, permissions).", s.rejects.load()),
      counter("tessera_resyncs_total", "Snapshots sent to clients whose queue overflowed.", s.resyncs.load()),
      gauge("tessera_queue_bytes", "Bytes queued for clients, summed over connections.",
            static_cast<double>(s.queueBytes.load())),
      gauge("tessera_queue_bytes_max", "Largest single client queue seen, bytes.",
            static_cast<double>(s.queueBytesMax.load())),
      counter("tessera_sent_bytes_total", "Bytes written to clients.", s.bytesSent.load()),
      counter("tessera_sent_frames_total", "Frames written to clients.", s.framesSent.load()),
      counter("tessera_delta_merges_total", "Queued deltas merged into later ones for slow clients.",
              s.deltaMerges.load()),
      counter("tessera_delta_flushes_total", "Deltas made, per view.", s.deltaFlushes.load()),
      counter("tessera_regions_encoded_total", "Regions Draco-encoded.", s.regionsEncoded.load()),
      counter("tessera_tiles_encoded_total", "Tiles of view-dependent subscriptions Draco-encoded.",
              s.tilesEncoded.load()),
      counter("tessera_tile_cache_hits_total", "Tiles sent from their cached encoding.",
              s.tileCacheHits.load()),
      gauge("tessera_tile_cache_bytes", "Encoded tiles held, bytes, over every document.",
            static_cast<double>(s.tileCacheBytes.load())),
      counter("tessera_store_entries_committed_total", "Journal entries made durable.",
              static_cast<int64_t>(store.entriesCommitted)),
      counter("tessera_store_entries_rejected_total", "Journal appends refused or lost to a failed commit.",
              static_cast<int64_t>(store.entriesRejected)),
      counter("tessera_store_batches_total", "Store transactions committed (one fsync each).",
              static_cast<int64_t>(store.batches)),
      histogram("tessera_edit_ack_seconds", "An edit from being applied to its durable ack.",
                s.ackLatency.snapshot()),
      histogram("tessera_store_commit_seconds", "One store transaction, BEGIN to durable COMMIT.",
                store.commitLatency),
      histogram("tessera_tessellate_seconds", "A view's tessellation build or update.",
                s.tessellateLatency.snapshot()),
      histogram("tessera_region_encode_seconds", "One region's Draco encoding.", s.encodeLatency.snapshot()),
  };
  return prometheus::TextSerializer().Serialize(families);
}

}  // namespace tessera::server
