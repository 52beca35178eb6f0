// The server's stats over one load run (docs/REPLAY.md §3.1, "server.window"):
// the StatsReply (docs/PROTOCOL.md §7.3) taken just before the first edit
// and again after the drain, and the differences. The server's own averages
// ("edits_per_second" = edits / uptime) cover its whole uptime, so after a
// busy run an idle one would still show the busy run's traffic.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "client/lib/session.h"
#include "core/util/status.h"

namespace tessera::replay {

using ServerStatsSample = std::map<std::string, double>;  // Stat name -> value

// One StatsReply, over a connection of its own.
Expected<ServerStatsSample> fetchServerStats(const client::SessionOptions& session);

// The window between two samples of one server:
//   "seconds": the difference of uptime_seconds (the server's clock);
//   counters (edits, rejects, bytes_sent, frames_sent, resyncs, deltas, ...):
//     their difference, and "<name>_per_second" over "seconds";
//   per-edit averages (tessellate_ms_per_edit, edit_to_durable_ms,
//     edits_per_delta, store_average_batch): recomputed over the window's
//     edits, deltas or batches alone (absent when the window has none);
//   gauges (connections, store_last_commit_ms): the value at the end.
// Stats either sample lacks are left out. An error if the server restarted
// in between (its uptime went down).
Expected<nlohmann::json> statsWindow(const ServerStatsSample& start, const ServerStatsSample& end);

}  // namespace tessera::replay
