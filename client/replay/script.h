// Replay scripts (docs/REPLAY.md): JSON lines of timed commands, one actor
// per line. The first line is a header naming the format and its version.
//
//   {"format":"tessera-replay","version":1,"document":1}
//   {"t":120,"actor":"editor-1","cmd":"move","vertex":"v2:40","mode":"offset","to":[0,0,0.01]}
//
// parseScript() checks everything it can without a server (ids parse, numbers
// are finite, times do not go backwards); errors are "FILE:LINE: reason".
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/util/status.h"
#include "protocol/tessera.pb.h"

namespace tessera::replay {

inline constexpr int kScriptVersion = 1;

struct ScriptHeader {
  uint64_t document = 0;   // 0: the caller must name one (--document)
  uint32_t baseLevel = 2;  // the profile a replay's final subscriber uses
  uint32_t maxLevel = 5;
  double angleDegrees = 10;
  std::string generator;  // free-form: the tool that wrote the script
};

struct ScriptCommand {
  enum class Kind { kMove, kCrease, kCorner, kInterpolate, kUndo, kRedo };
  int64_t timeMs = 0;
  std::string actor;
  Kind kind = Kind::kMove;
  std::vector<uint64_t> vertices;  // packed; kMove (one or more), kCorner and kInterpolate (one)
  bool offset = false;             // kMove: "mode":"offset" (else "direct")
  std::array<double, 3> to{};      // kMove target or displacement
  uint64_t edge = 0;               // kCrease, packed
  float sharpness = 0;             // kCrease, kCorner
  bool interpolating = true;       // kInterpolate: "on"
  double tension = 1.0;            // kInterpolate (docs/INTERPOLATION.md)
  // kUndo/kRedo: > 0 an edit id of the document; < 0 counts back through
  // the edits this actor made in this replay (-1: its latest).
  int64_t edit = 0;
  int line = 0;
};

struct Script {
  ScriptHeader header;
  std::vector<ScriptCommand> commands;
};

Expected<Script> parseScript(const std::string& text, const std::string& source);
Expected<Script> readScript(const std::string& path);

// One JSON line (no newline) for the header or a command.
std::string headerLine(const ScriptHeader& header);
std::string commandLine(const ScriptCommand& command);

// The wire command for `c` on `document`; `editId` resolves undo and redo.
wire::ClientMessage toWire(const ScriptCommand& c, uint64_t document, uint64_t editId);

// A synthetic script: `editors` actors, each `rate` edits per second for
// `seconds`, offsets of up to `step` on random vertices v<level>:0..count-1,
// with a crease or an undo of the actor's last edit now and then.
struct GenerateOptions {
  uint64_t document = 1;
  int editors = 2;
  double rate = 10;
  double seconds = 5;
  uint64_t seed = 1;
  int vertexLevel = 0;
  uint64_t vertexCount = 8;
  double step = 0.01;
  bool undo = true;
};
Script generateScript(const GenerateOptions& options);

}  // namespace tessera::replay
