// `tessera-replay load` on the command line: its options, thresholds and
// exit codes (docs/REPLAY.md §3).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "client/replay/replay_cli.h"

namespace tessera::replay {

// Exit codes of `load` beyond 0, 1 and 2 (docs/REPLAY.md §3.2). When
// several apply, the highest wins.
inline constexpr int kExitUncleanRun = 3;       // connection errors, gaps, viewers behind at the end
inline constexpr int kExitThresholdFailed = 4;  // a --threshold failed
inline constexpr int kExitStopped = 5;          // stopped: missing document, refused token

struct LoadArgs {
  ConnectionArgs connection;
  std::string viewerToken;
  std::string profile;
  uint64_t document = 0;
  int editors = 1, viewers = 10, decodeViewers = -1, vertexLevel = 0, serverPid = 0, poolThreads = 2;
  double rate = 10, seconds = 5, step = 0.01, drainSeconds = 10;
  std::string arrivals = "constant";
  double warmupSeconds = 0;
  std::string hgrmPrefix;
  int64_t maxEdits = 100000;
  uint64_t vertexCount = 8, seed = 1;
  bool displayOnly = false, quiet = false;
  std::string codec = "draco";  // --codec: the viewers' region codec
  std::string report;
  std::vector<std::string> thresholds;
  // View-dependent viewers (docs/REPLAY.md §3): a camera path and its sphere.
  std::string cameras;
  std::vector<double> cameraTarget;  // x y z radius
  std::string cameraSize = "390x844";
  double cameraTolerance = 1, cameraRate = 5;
};

CLI::App* addLoadCommand(CLI::App& app, LoadArgs& args);
int runLoadCommand(const LoadArgs& args);

}  // namespace tessera::replay
