#include "client/replay/load_report.h"

#include <sys/resource.h>
#include <sys/utsname.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "client/replay/latency_histogram.h"
#include "client/replay/latency_stats.h"
#include "client/replay/load_series.h"
#include "client/replay/send_schedule.h"
#include "tessera/version.h"

namespace tessera::replay {

namespace {

using nlohmann::json;

double round3(double x) {
  return std::round(x * 1000) / 1000;
}
double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

json histogramJson(const std::vector<double>& samples) {
  LatencyHistogram h;
  for (double ms : samples) h.addMilliseconds(ms);
  json buckets = json::array();
  for (const HistogramBucket& b : h.buckets()) buckets.push_back({b.lowerMicros, b.upperMicros, b.count});
  return buckets;
}

// The series' length: every second of editing begun, at least one.
size_t seriesSeconds(const LoadOptions& o, Shared& shared, const LoadRunData& run) {
  if (!run.started) return 0;
  double seconds = o.seconds;
  if (shared.stopped) seconds = std::min(seconds, std::max(0.0, shared.secondsSinceStart(shared.stoppedAt)));
  return std::max<size_t>(1, static_cast<size_t>(std::ceil(seconds - 1e-9)));
}

}  // namespace

json latencyJson(const std::vector<double>& samples) {
  const LatencySummary s = summarizeLatencies(samples);
  json j = {{"count", s.count}};
  if (s.count == 0) return j;
  j["mean"] = round3(s.mean);
  j["stddev"] = round3(s.stddev);
  j["min"] = round3(s.min);
  j["p50"] = round3(s.p50);
  j["p90"] = round3(s.p90);
  j["p95"] = round3(s.p95);
  j["p99"] = round3(s.p99);
  j["p99_9"] = round3(s.p999);
  j["max"] = round3(s.max);
  return j;
}

double processCpuSeconds() {
  rusage self{};
  getrusage(RUSAGE_SELF, &self);
  return static_cast<double>(self.ru_utime.tv_sec + self.ru_stime.tv_sec) +
         static_cast<double>(self.ru_utime.tv_usec + self.ru_stime.tv_usec) / 1e6;
}

namespace {

// The machine the run measured on, for the report (docs/REPLAY.md §3.3).
json machineJson() {
  json m = {{"cpus", std::thread::hardware_concurrency()}};
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      m["cpu_model"] = line.substr(line.find(':') + 2);
      break;
    }
  }
  utsname u{};
  if (uname(&u) == 0) m["kernel"] = std::string(u.sysname) + " " + u.release;
  return m;
}

// A send later than this after its due time counts as late.
constexpr double kLateMs = 1.0;

}  // namespace

json buildLoadReport(const LoadOptions& o, Shared& shared, const LoadRunData& run, LoadLatencies* latencies) {
  const double editSeconds =
      run.started ? std::chrono::duration<double>(run.editsDone - run.start).count() : 0.0;
  LoadSeries series(seriesSeconds(o, shared, run));
  for (size_t i = 0; i < shared.sentPerSecond.size(); ++i) series.sent(i, shared.sentPerSecond[i]);
  for (size_t i = 0; i < run.cpuPerSecond.size(); ++i)
    series.cpu(i, run.cpuPerSecond[i].tester, run.cpuPerSecond[i].server);
  // Edits due in the warm-up are in the series and counts, not in the
  // latency figures.
  auto warm = [&](double dueSeconds) { return dueSeconds >= o.warmupSeconds; };
  int64_t warmupAcks = 0, warmupDeltas = 0;
  std::vector<double> toAck;
  toAck.reserve(shared.ackSamples.size());
  for (const TimedSample& s : shared.ackSamples) {
    series.acked(s.sentSeconds, s.ms);
    if (warm(s.sentSeconds)) {
      toAck.push_back(s.ms);
    } else {
      ++warmupAcks;
    }
  }
  for (double t : shared.rejectedAt) series.rejected(t);
  for (Clock::time_point t : shared.errorTimes) series.error(shared.secondsSinceStart(t));

  // Edit to delta: the send time of the edit whose Ack carried version V
  // against the arrival of the delta that brought the viewer to V (a delta
  // spans several versions when the server or a full queue batched edits).
  std::vector<double> toDelta;
  // View-dependent viewers: edit to the delta that brought tiles, for the
  // viewers whose view the edit reached (a delta without tiles only moves
  // the version of a viewer that does not show it).
  std::vector<double> toTiles;
  int64_t tilesReceived = 0;
  int64_t deltaBytes = 0, snapshotBytes = 0, readyViewers = 0, presenceBytes = 0, presenceMessages = 0;
  uint64_t minVersion = UINT64_MAX, maxVersion = 0;
  std::set<uint64_t> hashes;
  int decodedReady = 0;
  int64_t behind = 0;
  for (const ViewerResult& v : run.viewers) {
    if (v.version < shared.maxAckedVersion) ++behind;
    deltaBytes += v.deltaBytes;
    tilesReceived += v.regionsReceived;
    presenceBytes += v.presenceBytes;
    presenceMessages += v.presenceMessages;
    snapshotBytes += v.snapshotBytes;
    if (v.ready) ++readyViewers;
    minVersion = std::min(minVersion, v.version);
    maxVersion = std::max(maxVersion, v.version);
    if (v.decoded && v.hash != 0 && v.version == shared.maxAckedVersion)
      hashes.insert(v.hash), ++decodedReady;
    for (const auto& d : v.deltaTimes) {
      for (uint64_t version = d.fromVersion + 1; version <= d.toVersion; ++version) {
        auto it = shared.sendTimeOfVersion.find(version);
        if (it == shared.sendTimeOfVersion.end()) continue;
        const double ms = msBetween(it->second, d.arrival);
        const double due = msBetween(run.start, it->second) / 1000;
        series.delta(due, ms);
        if (!warm(due)) {
          ++warmupDeltas;
          continue;
        }
        toDelta.push_back(ms);
        if (o.cameras && d.regions > 0) toTiles.push_back(ms);
      }
    }
  }
  if (run.viewers.empty()) minVersion = 0;
  const int viewers = o.viewers;

  json report;
  report["format"] = "tessera-replay-report";
  // Version 2: latencies and the series count from each edit's due time
  // (send_schedule.h), not from when it went out.
  report["version"] = 2;
  report["config"] = {
      {"document", o.document},
      {"editors", o.editors},
      {"viewers", o.viewers},
      {"rate_per_editor", o.rate},
      {"arrivals", arrivalsName(o.arrivals)},
      {"warmup_seconds", o.warmupSeconds},
      {"seconds", o.seconds},
      {"max_edits_per_editor", o.maxEdits},
      {"profile", {o.profile.base_level(), o.profile.max_level(), o.profile.angle_threshold_degrees()}},
      {"display_only", o.profile.omit_vertex_ids()},
      {"decoding_viewers", run.decodingViewers},
      {"vertices", "v" + std::to_string(o.vertexLevel) + ":0.." + std::to_string(o.vertexCount - 1)}};
  if (shared.stopped) {
    report["stopped"] = {
        {"reason", shared.stopReason},
        {"after_seconds", round3(std::chrono::duration<double>(shared.stoppedAt - run.begin).count())}};
  }
  report["connect_ms"] = std::round(run.connectMs);
  report["settle_ms"] = std::round(run.settleMs);
  report["edit_seconds"] = editSeconds;
  // The open model's account (send_schedule.h): offered is what the
  // schedule made due, achieved what went out; late sends went out more
  // than kLateMs after they were due, dropped ones never.
  const int64_t sent = shared.sent.load(), dropped = shared.dropped.load();
  const int64_t late =
      std::count_if(shared.lateness.begin(), shared.lateness.end(), [](double ms) { return ms > kLateMs; });
  const bool testerBehind = dropped > 0 || 100 * late > sent;
  report["edits"] = {{"sent", sent},
                     {"acked", shared.acked.load()},
                     {"rejected", shared.rejected.load()},
                     {"throughput_per_second", editSeconds > 0 ? shared.acked / editSeconds : 0.0},
                     {"offered", sent + dropped},
                     {"offered_per_second", run.started ? (sent + dropped) / o.seconds : 0.0},
                     {"achieved_per_second", run.started ? sent / o.seconds : 0.0},
                     {"late", late},
                     {"late_threshold_ms", kLateMs},
                     {"dropped", dropped},
                     {"lateness_ms", latencyJson(shared.lateness)},
                     {"tester_behind", testerBehind}};
  report["latency_ms"] = {{"edit_to_ack", latencyJson(toAck)}, {"edit_to_delta", latencyJson(toDelta)}};
  report["warmup_excluded"] = {{"edit_to_ack", warmupAcks}, {"edit_to_delta", warmupDeltas}};
  if (o.cameras) {
    report["config"]["cameras"] = {
        {"path", cameraPathName(o.cameras->kind)},
        {"centre", {o.cameras->centre[0], o.cameras->centre[1], o.cameras->centre[2]}},
        {"radius", o.cameras->radius},
        {"size", {o.cameras->width, o.cameras->height}},
        {"tolerance_pixels", o.cameras->tolerancePixels},
        {"views_per_second", o.cameras->viewsPerSecond}};
    report["latency_ms"]["edit_to_tiles"] = latencyJson(toTiles);
  }
  report["histograms"] = {{"unit", "us"},
                          {"layout", "log-linear: [v, v+1) below 8 us, then 8 buckets per power of two"},
                          {"edit_to_ack", histogramJson(toAck)},
                          {"edit_to_delta", histogramJson(toDelta)}};
  report["series"] = series.toJson();
  report["final_version"] = shared.maxAckedVersion.load();
  report["viewers"] = {
      {"ready_at_end", readyViewers},
      {"gaps", shared.gaps.load()},
      {"resyncs", shared.resyncs.load()},
      {"deltas", shared.deltas.load()},
      {"snapshot_bytes_per_viewer", viewers ? snapshotBytes / viewers : 0},
      {"delta_bytes_per_viewer", viewers ? deltaBytes / viewers : 0},
      {"bytes_per_second_per_viewer", viewers && editSeconds > 0 ? deltaBytes / viewers / editSeconds : 0.0},
      {"delta_regions_per_second_per_viewer",
       viewers && editSeconds > 0 ? static_cast<double>(tilesReceived) / viewers / editSeconds : 0.0},
      {"version_min", minVersion},
      {"version_max", maxVersion},
      {"behind_at_end", behind},
      {"presence_messages_per_viewer", viewers ? presenceMessages / viewers : 0},
      {"presence_bytes_per_viewer", viewers ? presenceBytes / viewers : 0},
      {"decoded_at_final_version", decodedReady},
      {"decoded_hashes_agree", hashes.size() <= 1}};
  report["errors"] = {{"count", shared.errors.load()}, {"messages", shared.errorMessages}};
  json server = json::object();
  if (run.cpuBefore.ok && run.cpuAfter.ok) {
    server["pid"] = o.serverPid;
    server["cpu_percent"] = std::round(1000 * (run.cpuAfter.cpuSeconds - run.cpuBefore.cpuSeconds) /
                                       std::max(editSeconds, 1e-3)) /
                            10;
    server["rss_bytes"] = run.cpuAfter.rssBytes;
    server["rss_peak_bytes"] = run.rssPeak;
  }
  if (run.statsEnd) server["stats"] = *run.statsEnd;
  if (run.statsStart && run.statsEnd) {
    auto window = statsWindow(*run.statsStart, *run.statsEnd);
    if (window.isOk()) {
      server["window"] = *window;
    } else {
      server["window_error"] = window.status().message();
    }
  } else if (run.started) {
    server["window_error"] = run.statsError;
  }
  report["server"] = server;
  const double cpu = processCpuSeconds();
  report["client"] = {
      {"cpu_seconds", std::round(cpu * 100) / 100},
      {"threads", o.editors + run.threadedViewers + (o.viewers > run.threadedViewers ? run.poolThreads : 0)},
      {"pooled_viewers", o.viewers - run.threadedViewers}};
  if (run.started && editSeconds > 0) {
    // Beside the server's: the tester's own CPU over the same window.
    report["client"]["cpu_percent"] =
        std::round(1000 * (run.testerCpuAfter - run.testerCpuBefore) / editSeconds) / 10;
  }
  report["machine"] = machineJson();
  report["versions"] = {{"tessera_replay", kVersion}};
  if (latencies) *latencies = {std::move(toAck), std::move(toDelta), std::move(toTiles)};
  return report;
}

std::string summarize(const json& r) {
  auto lat = [](const char* label, const json& p) {
    char buf[256];
    if (p.value("count", 0) == 0) {
      std::snprintf(buf, sizeof buf, "  %-15s (no samples)\n", label);
    } else {
      std::snprintf(buf, sizeof buf, "  %-15s %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8lld\n", label,
                    p["mean"].get<double>(), p["stddev"].get<double>(), p["p50"].get<double>(),
                    p["p90"].get<double>(), p["p95"].get<double>(), p["p99"].get<double>(),
                    p["p99_9"].get<double>(), p["max"].get<double>(), p["count"].get<long long>());
    }
    return std::string(buf);
  };
  char line[256];
  std::ostringstream out;
  const json& c = r["config"];
  std::snprintf(line, sizeof line, "tessera-replay load: %d editors x %g/s, %d viewers, %.2f s\n",
                c["editors"].get<int>(), c["rate_per_editor"].get<double>(), c["viewers"].get<int>(),
                r["edit_seconds"].get<double>());
  out << line;
  if (r.contains("stopped")) {
    out << "  STOPPED after " << r["stopped"]["after_seconds"].get<double>()
        << " s: " << r["stopped"]["reason"].get<std::string>() << "\n";
  }
  const json& e = r["edits"];
  std::snprintf(line, sizeof line, "  edits: %lld acked of %lld sent, %lld rejected, %.2f acked/s\n",
                e["acked"].get<long long>(), e["sent"].get<long long>(), e["rejected"].get<long long>(),
                e["throughput_per_second"].get<double>());
  out << line;
  if (e.contains("offered")) {
    std::snprintf(line, sizeof line,
                  "  schedule (%s): offered %.2f/s, achieved %.2f/s; %lld late by more than %g ms, %lld "
                  "dropped\n",
                  c["arrivals"].get<std::string>().c_str(), e["offered_per_second"].get<double>(),
                  e["achieved_per_second"].get<double>(), e["late"].get<long long>(),
                  e["late_threshold_ms"].get<double>(), e["dropped"].get<long long>());
    out << line;
    if (e["tester_behind"].get<bool>()) {
      const json& l = e["lateness_ms"];
      std::snprintf(line, sizeof line,
                    "  WARNING: the tester fell behind its schedule (lateness p99 %.2f ms, max %.2f ms): its "
                    "own delay is in these latencies; use fewer connections or a second machine\n",
                    l.value("p99", 0.0), l.value("max", 0.0));
      out << line;
    }
  }
  if (c.contains("warmup_seconds") && c["warmup_seconds"].get<double>() > 0) {
    std::snprintf(
        line, sizeof line,
        "  warm-up: the first %g s of edits are left out of the latencies (%lld acks, %lld deltas)\n",
        c["warmup_seconds"].get<double>(), r["warmup_excluded"]["edit_to_ack"].get<long long>(),
        r["warmup_excluded"]["edit_to_delta"].get<long long>());
    out << line;
  }
  out << "  latency (ms)        mean   stddev      p50      p90      p95      p99    p99.9      max        "
         "n\n";
  out << lat("edit -> ack", r["latency_ms"]["edit_to_ack"]);
  out << lat("edit -> delta", r["latency_ms"]["edit_to_delta"]);
  if (r["latency_ms"].contains("edit_to_tiles"))
    out << lat("edit -> tiles", r["latency_ms"]["edit_to_tiles"]);
  const json& v = r["viewers"];
  std::snprintf(line, sizeof line,
                "  viewers: %lld ready, %lld behind the last acked version at the end, gaps %lld, resyncs "
                "%lld, %.1f KiB/s "
                "each (snapshot %lld B)\n",
                v["ready_at_end"].get<long long>(), v["behind_at_end"].get<long long>(),
                v["gaps"].get<long long>(), v["resyncs"].get<long long>(),
                v["bytes_per_second_per_viewer"].get<double>() / 1024,
                v["snapshot_bytes_per_viewer"].get<long long>());
  out << line;
  out << "  errors: " << r["errors"]["count"] << "\n";
  const json& s = r["server"];
  if (s.contains("cpu_percent")) {
    out << "  server: cpu " << s["cpu_percent"] << " %, rss " << (s["rss_bytes"].get<int64_t>() >> 20)
        << " MiB (peak " << (s["rss_peak_bytes"].get<int64_t>() >> 20) << " MiB)";
    if (r["client"].contains("cpu_percent")) out << "; tester: cpu " << r["client"]["cpu_percent"] << " %";
    out << "\n";
  } else if (r["client"].contains("cpu_percent")) {
    out << "  tester: cpu " << r["client"]["cpu_percent"] << " %\n";
  }
  if (s.contains("window")) {
    const json& w = s["window"];
    auto count = [&](const char* k) { return w.contains(k) ? w[k].get<double>() : 0.0; };
    std::snprintf(
        line, sizeof line,
        "  server over the run (%.2f s): %.0f edits (%.1f/s), %.0f rejects, %.0f resyncs, %.0f deltas, "
        "%.1f KiB sent (%.1f KiB/s)",
        w["seconds"].get<double>(), count("edits"), count("edits_per_second"), count("rejects"),
        count("resyncs"), count("deltas"), count("bytes_sent") / 1024, count("bytes_sent_per_second") / 1024);
    out << line;
    if (w.contains("tessellate_ms_per_edit")) {
      std::snprintf(line, sizeof line, ", tessellate %.3f ms/edit",
                    w["tessellate_ms_per_edit"].get<double>());
      out << line;
    }
    out << "\n";
    if (w.contains("tile_cache_hit_ratio")) {
      std::snprintf(
          line, sizeof line,
          "  tiles over the run: %.0f encoded (%.1f/s), %.0f sent from the cache (hit ratio %.1f %%), "
          "%.0f of %.0f views applied\n",
          count("tiles_encoded"), count("tiles_encoded_per_second"), count("tile_cache_hits"),
          100 * w["tile_cache_hit_ratio"].get<double>(), count("views_applied"), count("views_received"));
      out << line;
    }
  } else if (s.contains("window_error")) {
    out << "  server over the run: n/a (" << s["window_error"].get<std::string>() << ")\n";
  }
  return out.str();
}

}  // namespace tessera::replay
