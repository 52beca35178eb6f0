// Edit scripts for `tessera doc edit --script FILE`: one command per line,
// `#` starts a comment, ids as printed by `tessera doc info`:
//
//   move v2:40 [v2:41 ...] to X Y Z     direct manipulation: the first vertex's
//                                       limit goes to (X, Y, Z); the others
//                                       move by the same amount (§2.2)
//   offset v3:7 [v3:8 ...] by DX DY DZ  plain displacement of control points
//   crease e1:5 S                       edge sharpness at that level (S or inf)
//   corner v4:900 S                     vertex sharpness: 0 smooth, > 0 corner/cusp
//   interpolate v1:30 [T] [tangent X Y Z]
//                                       the surface passes through the vertex's
//                                       control point (docs/INTERPOLATION.md), tension T
//                                       (default 1); a tangent line for boundary
//                                       and crease vertices
//   interpolate v1:30 off               back to plain Loop
//   undo N | redo N | remove N          by edit id (N or editN)
//
// A script applies entirely or not at all: the first bad line is reported as
// "FILE:LINE: reason" and the document is left as it was.
#pragma once

#include <string>
#include <vector>

#include <string>

#include "core/document/document.h"
#include "core/util/status.h"

namespace tessera {

struct ScriptResult {
  int commands = 0;  // lines that did something
};

// One parsed line: what to do, independent of where it is done (a local
// document, or a server through the client library).
struct ScriptCommand {
  enum class Kind { kMove, kOffset, kCrease, kCorner, kInterpolate, kUndo, kRedo, kRemove };
  Kind kind;
  std::vector<VertexId> vertices;  // kMove, kOffset, kCorner, kInterpolate
  EdgeId edge;                     // kCrease
  Vec3 value;                      // kMove target, kOffset displacement, kInterpolate tangent
  float sharpness = 0.0f;          // kCrease, kCorner
  bool interpolating = true;       // kInterpolate
  double tension = 1.0;            // kInterpolate
  EditId edit;                     // kUndo, kRedo, kRemove
  int line = 0;
};

// Errors are "SOURCE:LINE: reason".
Expected<std::vector<ScriptCommand>> parseEditScript(const std::string& text, const std::string& source);
Status applyScriptCommand(const ScriptCommand& command, Document& document);
// Takes back a command applyScriptCommand just applied, leaving the document
// as it was before it (a replay refusing a command the way a server does).
// A remove cannot be taken back: kUnsupported.
Status takeBackScriptCommand(const ScriptCommand& command, Document& document);

Expected<ScriptResult> applyEditScript(const std::string& text, const std::string& source,
                                       Document& document);

}  // namespace tessera
