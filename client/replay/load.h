// A bounded load run (docs/REPLAY.md §3): E editor connections each sending paced
// edits at R per second, M viewer connections each subscribed and checking
// version continuity, all on loopback, all bounded in time and count. The
// result is the machine-readable report of docs/REPLAY.md.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "client/lib/session.h"
#include "client/replay/camera_path.h"
#include "client/replay/send_schedule.h"
#include "core/util/status.h"
#include "protocol/tessera.pb.h"

namespace tessera::replay {

struct LoadOptions {
  client::SessionOptions session;  // host, port, the editors' token
  std::string viewerToken;         // empty: the editors' token
  uint64_t document = 0;
  int editors = 1;
  int viewers = 10;
  double rate = 10;  // edits per second per editor
  // When editors send (send_schedule.h): a schedule fixed before the run.
  Arrivals arrivals = Arrivals::kConstant;
  // Edits due in the first seconds of editing are sent and counted, but
  // left out of the latency figures (docs/REPLAY.md §3.3).
  double warmupSeconds = 0;
  // Set: the latency samples also go to PREFIX-edit_to_ack.hgrm, ... (hgrm.h).
  std::string hgrmPrefix;
  double seconds = 5;                                        // editing time
  int64_t maxEdits = 100000;                                 // per editor
  wire::LodProfile profile;                                  // the viewers' profile
  wire::RegionCodec codec = wire::REGION_CODEC_UNSPECIFIED;  // the viewers' region codec (unset: Draco)
  int decodeViewers = -1;  // viewers that decode with DocumentView; -1: min(viewers, 20)
  int vertexLevel = 0;     // edits move v<level>:0..vertexCount-1
  uint64_t vertexCount = 8;
  double step = 0.01;  // largest offset per axis
  uint64_t seed = 1;
  double drainSeconds = 10;      // after editing: waiting for acks and the last deltas
  double connectSeconds = 120;   // connecting and subscribing every viewer
  int serverPid = 0;             // > 0: sample its CPU and RSS from /proc
  bool progress = true;          // one line per second on stderr
  double viewerPollSeconds = 1;  // a ready viewer's receive timeout (checks for the end)
  int poolThreads = 2;           // threads of the counting viewers' pool; 0: a thread per viewer
  // Set: view-dependent viewers, each on its own camera path, sending
  // SetView at cameras->viewsPerSecond (docs/REPLAY.md §3, docs/VIEWS.md).
  std::optional<CameraPaths> cameras;
};

Expected<nlohmann::json> runLoad(const LoadOptions& options);

// A few lines for people.
std::string summarize(const nlohmann::json& report);

}  // namespace tessera::replay
