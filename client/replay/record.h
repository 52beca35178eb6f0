// Recording a live session as a replay script (docs/REPLAY.md §2.1): a
// subscriber that asks for the commands (Subscribe.with_commands) turns each
// durable AppliedCommand into one script line, in version order. Replaying
// the script on a copy of the document at the recording's start version ends
// at the same surface. ScriptRecorder is the conversion alone; runRecord()
// is the connection around it.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "client/lib/session.h"
#include "client/replay/replay.h"
#include "client/replay/script.h"

namespace tessera::replay {

class ScriptRecorder {
 public:
  // `startServerMs`: the server's clock at the start of the recording (t = 0).
  explicit ScriptRecorder(uint64_t startServerMs) : startMs_(startServerMs) {}

  // The script line for one command. Each author session is one actor,
  // named after its client name; a second session with a name already taken
  // becomes "NAME#2". An undo or redo of an edit its own actor made during
  // the recording uses a relative id (-1: the actor's latest), otherwise the
  // absolute edit id. Errors: no command in it, more than 1000 actors.
  Expected<ScriptCommand> add(const wire::AppliedCommand& c);
  // The script lines of `c`: one, or one per command of an EditBatch (a
  // script has no batches; replayed one by one they reach the same state,
  // as each command of a batch sees the ones before it).
  Expected<std::vector<ScriptCommand>> lines(const wire::AppliedCommand& c);
  size_t actors() const { return actorOf_.size(); }

 private:
  std::string actorFor(uint64_t session, const std::string& name);

  uint64_t startMs_;
  int64_t lastMs_ = 0;
  std::map<uint64_t, std::string> actorOf_;  // author session -> actor
  std::set<std::string> taken_;
  std::map<std::string, std::vector<uint64_t>> edits_;  // actor -> its edit ids, oldest first
};

struct RecordOptions {
  client::SessionOptions session;  // the recorder's own connection (any role that may open the document)
  uint64_t document = 0;
  ScriptHeader header;          // its profile is the recorder's subscription and goes into the script
  double seconds = 0;           // stop after this long (0: only --until-version)
  uint64_t untilVersion = 0;    // stop once the command making this version is recorded (0: none)
  double drainSeconds = 2;      // after a timed stop: catch up with deltas already received
  std::ostream* out = nullptr;  // the script, written and flushed line by line
  std::function<void(uint64_t fromVersion)> started;  // once subscribed, before any command
};

struct RecordResult {
  uint64_t fromVersion = 0;  // the document's version when the recording started
  uint64_t lastVersion = 0;  // made by the last recorded command (fromVersion if none)
  int64_t commands = 0;
  size_t actors = 0;
  // The recorder's decoded view at lastVersion, with the header's profile;
  // unset if the view was elsewhere at the end (a resync, a dropped profile).
  std::optional<SurfaceState> surface;
  // Why the recording ended early (a lost connection, an unreached
  // --until-version); ok when it ended as asked. What came before is written.
  Status stopped;
};

// Errors before the first line: connecting, opening or subscribing.
Expected<RecordResult> runRecord(const RecordOptions& options);

}  // namespace tessera::replay
