// Replaying a script (docs/REPLAY.md) against a server, and reading the
// document's final surface: one connection per actor, commands sent in script
// order and each acknowledged before the next, so that the server's total
// order -- and therefore the final surface hash -- is the script's.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "client/replay/script.h"

namespace tessera::replay {

struct ReplayOptions {
  client::SessionOptions session;  // host, port, token; the name is the actor's
  uint64_t document = 0;           // 0: the script header's
  double speed = 1;                // 1: real time; 2: twice as fast; 0: no waiting
  double replyTimeoutSeconds = 30;
};

struct ReplayResult {
  int commands = 0;
  int acked = 0;
  int rejected = 0;
  uint64_t lastVersion = 0;  // of the last Ack
};

Expected<ReplayResult> runReplay(const Script& script, const ReplayOptions& options);

Status openDocument(client::Session& session, uint64_t document, double timeoutSeconds);
// Opens and subscribes `session` to `document`, waits for the snapshot.
// `withCommands`: the server also sends every later command
// (AppliedCommand, client/lib/command_feed.h).
Status openAndSubscribe(client::Session& session, uint64_t document, const wire::LodProfile& profile,
                        client::DocumentView* view, double timeoutSeconds, bool withCommands = false);

struct SurfaceState {
  uint64_t version = 0;
  uint64_t hash = 0;
  int64_t triangles = 0;
};
// A fresh subscriber's view of `document` with `profile`.
Expected<SurfaceState> readSurface(const client::SessionOptions& session, uint64_t document,
                                   const wire::LodProfile& profile);

wire::LodProfile profileOf(const ScriptHeader& header);

// Seconds as a steady_clock duration, for deadlines and pacing.
inline std::chrono::steady_clock::duration secondsOf(double seconds) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(seconds));
}

}  // namespace tessera::replay
