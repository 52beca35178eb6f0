// One counter of the server's StatsReply (docs/PROTOCOL.md, stats), read
// through a session; -1 when the call fails or the counter is not there.
#pragma once

#include <string>

#include "client/lib/session.h"

namespace tessera::testing {

inline double serverStat(client::Session& s, const std::string& name) {
  wire::ClientMessage m;
  m.mutable_stats();
  auto reply = s.call(m, 10);
  if (!reply.isOk() || !reply->has_stats_reply()) return -1;
  for (const auto& stat : reply->stats_reply().stats()) {
    if (stat.name() == name) return stat.value();
  }
  return -1;
}

}  // namespace tessera::testing
