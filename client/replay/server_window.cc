#include "client/replay/server_window.h"

#include <cmath>

namespace tessera::replay {

namespace {

// Cumulative counters of StatsReply (server/connection.cc, Connection::stats).
constexpr const char* kCounters[] = {
    "connections_total", "edits",        "rejects",       "bytes_sent",      "frames_sent",
    "delta_merges",      "resyncs",      "deltas",        "delta_regions",   "delta_regions_layout_ids",
    "store_batches",     "tiles_built",  "tiles_encoded", "tile_cache_hits", "tile_cache_evictions",
    "views_received",    "views_applied"};
// Counters whose rate is worth reporting.
constexpr const char* kRated[] = {"edits",   "rejects", "bytes_sent",    "frames_sent",
                                  "resyncs", "deltas",  "tiles_encoded", "views_applied"};
// Values that describe the moment, not a sum: the end's is reported.
constexpr const char* kGauges[] = {"connections", "store_last_commit_ms"};

// An average A = total / N the server keeps over its uptime, as the average
// over the window: (A1 * N1 - A0 * N0) / (N1 - N0).
struct Average {
  const char* name;
  const char* per;  // the counter it is an average over
};
constexpr Average kAverages[] = {{"tessellate_ms_per_edit", "edits"},
                                 {"edit_to_durable_ms", "edits"},
                                 {"store_average_batch", "store_batches"}};

const double* find(const ServerStatsSample& s, const std::string& name) {
  auto it = s.find(name);
  return it == s.end() ? nullptr : &it->second;
}

double round6(double x) {
  return std::round(x * 1e6) / 1e6;
}

}  // namespace

Expected<ServerStatsSample> fetchServerStats(const client::SessionOptions& session) {
  client::SessionOptions o = session;
  o.name = "tessera-replay-stats";
  TESSERA_ASSIGN_OR_RETURN(auto s, client::Session::connect(o));
  wire::ClientMessage m;
  m.mutable_stats();
  auto reply = s->call(m, 10);
  s->close();
  if (!reply.isOk()) return reply.status().withContext("stats");
  if (!reply->has_stats_reply())
    return ioError("stats: the server answered with something else than a StatsReply");
  ServerStatsSample sample;
  for (const auto& stat : reply->stats_reply().stats()) sample[stat.name()] = stat.value();
  return sample;
}

Expected<nlohmann::json> statsWindow(const ServerStatsSample& start, const ServerStatsSample& end) {
  const double* up0 = find(start, "uptime_seconds");
  const double* up1 = find(end, "uptime_seconds");
  if (!up0 || !up1) return invalidArgument("stats window: no uptime_seconds in the server's stats");
  if (*up1 < *up0)
    return invalidArgument("stats window: the server's uptime went down (a restart during the run?)");
  const double seconds = *up1 - *up0;
  nlohmann::json w = {{"seconds", round6(seconds)}};
  for (const char* name : kCounters) {
    const double* a = find(start, name);
    const double* b = find(end, name);
    if (a && b) w[name] = *b - *a;
  }
  for (const char* name : kRated) {
    if (w.contains(name) && seconds > 0)
      w[std::string(name) + "_per_second"] = round6(w[name].get<double>() / seconds);
  }
  for (const Average& avg : kAverages) {
    const double *a0 = find(start, avg.name), *a1 = find(end, avg.name);
    const double *n0 = find(start, avg.per), *n1 = find(end, avg.per);
    if (!a0 || !a1 || !n0 || !n1 || *n1 - *n0 <= 0) continue;
    w[avg.name] = round6((*a1 * *n1 - *a0 * *n0) / (*n1 - *n0));
  }
  // View-dependent subscriptions: the share of tile payloads sent from the
  // cache rather than encoded for them.
  if (w.contains("tile_cache_hits") && w.contains("tiles_encoded")) {
    const double sent = w["tile_cache_hits"].get<double>() + w["tiles_encoded"].get<double>();
    if (sent > 0) w["tile_cache_hit_ratio"] = round6(w["tile_cache_hits"].get<double>() / sent);
  }
  if (w.contains("edits") && w.contains("deltas") && w["deltas"].get<double>() > 0) {
    w["edits_per_delta"] = round6(w["edits"].get<double>() / w["deltas"].get<double>());
  }
  for (const char* name : kGauges) {
    if (const double* v = find(end, name)) w[name] = *v;
  }
  return w;
}

}  // namespace tessera::replay
