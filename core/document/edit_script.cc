#include "core/document/edit_script.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "core/util/text.h"

namespace tessera {

namespace {

bool parseDouble(const std::string& token, double& value) {
  const char* end = token.data() + token.size();
  auto [p, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && p == end && std::isfinite(value);
}

bool parseSharpness(const std::string& token, float& value) {
  if (token == "inf" || token == "INF" || token == "Inf") {
    value = kSharpnessInfinite;
    return true;
  }
  double d = 0;
  if (!parseDouble(token, d)) return false;
  value = static_cast<float>(d);
  return true;
}

Expected<EditId> parseEditId(const std::string& token) {
  std::string digits = token.rfind("edit", 0) == 0 ? token.substr(4) : token;
  uint64_t value = 0;
  const char* end = digits.data() + digits.size();
  auto [p, ec] = std::from_chars(digits.data(), end, value);
  if (digits.empty() || ec != std::errc() || p != end) return parseError("bad edit id '" + token + "'");
  return EditId{value};
}

// "v2:40 v2:41 to X Y Z": ids up to the keyword, then three numbers.
Status parseMove(const std::vector<std::string>& t, const char* keyword, std::vector<VertexId>& ids,
                 Vec3& value) {
  size_t k = 1;
  for (; k < t.size() && t[k] != keyword; ++k) {
    TESSERA_ASSIGN_OR_RETURN(VertexId id, parseVertexId(t[k]));
    ids.push_back(id);
  }
  if (k == t.size()) return parseError(std::string("expected '") + keyword + " X Y Z'");
  if (t.size() != k + 4) return parseError(std::string("expected three numbers after '") + keyword + "'");
  for (int i = 0; i < 3; ++i) {
    if (!parseDouble(t[k + 1 + i], value[i])) return parseError("bad number '" + t[k + 1 + i] + "'");
  }
  return Status::ok();
}

Expected<ScriptCommand> parseLine(const std::vector<std::string>& t) {
  using Kind = ScriptCommand::Kind;
  const std::string& cmd = t[0];
  ScriptCommand c{};
  if (cmd == "move" || cmd == "offset") {
    c.kind = cmd == "move" ? Kind::kMove : Kind::kOffset;
    TESSERA_RETURN_IF_ERROR(parseMove(t, cmd == "move" ? "to" : "by", c.vertices, c.value));
    return c;
  }
  if (cmd == "crease" || cmd == "corner") {
    if (t.size() != 3) return parseError("expected '" + cmd + " ID SHARPNESS'");
    if (!parseSharpness(t[2], c.sharpness)) return parseError("bad sharpness '" + t[2] + "'");
    if (cmd == "crease") {
      c.kind = Kind::kCrease;
      TESSERA_ASSIGN_OR_RETURN(c.edge, parseEdgeId(t[1]));
      return c;
    }
    c.kind = Kind::kCorner;
    TESSERA_ASSIGN_OR_RETURN(VertexId vertex, parseVertexId(t[1]));
    c.vertices.push_back(vertex);
    return c;
  }
  if (cmd == "interpolate") {
    if (t.size() < 2)
      return parseError("expected 'interpolate ID [TENSION] [tangent X Y Z]' or 'interpolate ID off'");
    c.kind = Kind::kInterpolate;
    c.value = Vec3(0, 0, 0);
    TESSERA_ASSIGN_OR_RETURN(VertexId vertex, parseVertexId(t[1]));
    c.vertices.push_back(vertex);
    size_t k = 2;
    if (k < t.size() && t[k] == "off") {
      if (t.size() != 3) return parseError("nothing may follow 'off'");
      c.interpolating = false;
      return c;
    }
    if (k < t.size() && t[k] != "tangent") {
      if (!parseDouble(t[k], c.tension)) return parseError("bad tension '" + t[k] + "'");
      ++k;
    }
    if (k < t.size()) {
      if (t[k] != "tangent" || t.size() != k + 4)
        return parseError("expected 'tangent X Y Z' after the tension");
      for (int i = 0; i < 3; ++i) {
        if (!parseDouble(t[k + 1 + i], c.value[i])) return parseError("bad number '" + t[k + 1 + i] + "'");
      }
    }
    return c;
  }
  if (cmd == "undo" || cmd == "redo" || cmd == "remove") {
    if (t.size() != 2) return parseError("expected '" + cmd + " EDIT'");
    c.kind = cmd == "undo" ? Kind::kUndo : cmd == "redo" ? Kind::kRedo : Kind::kRemove;
    TESSERA_ASSIGN_OR_RETURN(c.edit, parseEditId(t[1]));
    return c;
  }
  return parseError("unknown command '" + cmd +
                    "' (move, offset, crease, corner, interpolate, undo, redo, remove)");
}

}  // namespace

Expected<std::vector<ScriptCommand>> parseEditScript(const std::string& text, const std::string& source) {
  std::vector<ScriptCommand> commands;
  std::istringstream in(text);
  std::string line;
  int lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const std::vector<std::string> tokens = splitTokens(line);
    if (tokens.empty()) continue;
    auto command = parseLine(tokens);
    if (!command.isOk()) {
      return Status(command.status().code(),
                    source + ":" + std::to_string(lineNumber) + ": " + command.status().message());
    }
    command->line = lineNumber;
    commands.push_back(std::move(*command));
  }
  return commands;
}

Status applyScriptCommand(const ScriptCommand& c, Document& doc) {
  using Kind = ScriptCommand::Kind;
  switch (c.kind) {
    case Kind::kMove:
      return doc.moveToLimit(c.vertices, c.value).status();
    case Kind::kOffset:
      return doc.moveBy(c.vertices, c.value).status();
    case Kind::kCrease:
      return doc.setEdgeSharpness(c.edge, c.sharpness).status();
    case Kind::kCorner:
      return doc.setVertexSharpness(c.vertices[0], c.sharpness).status();
    case Kind::kInterpolate:
      return doc.setInterpolation(c.vertices[0], c.interpolating, c.tension, c.value).status();
    case Kind::kUndo:
      return doc.undo(c.edit);
    case Kind::kRedo:
      return doc.redo(c.edit);
    case Kind::kRemove:
      return doc.remove(c.edit);
  }
  return internalError("unknown script command");
}

Status takeBackScriptCommand(const ScriptCommand& c, Document& doc) {
  using Kind = ScriptCommand::Kind;
  switch (c.kind) {
    case Kind::kUndo:
      return doc.reinstate(c.edit);
    case Kind::kRedo:
      return doc.undo(c.edit);
    case Kind::kRemove:
      return unsupported("a remove cannot be taken back");
    default:
      return doc.retractLast();
  }
}

Expected<ScriptResult> applyEditScript(const std::string& text, const std::string& source,
                                       Document& document) {
  TESSERA_ASSIGN_OR_RETURN(std::vector<ScriptCommand> commands, parseEditScript(text, source));
  Document working = document;  // all or nothing
  for (const ScriptCommand& c : commands) {
    Status status = applyScriptCommand(c, working);
    if (!status.isOk())
      return Status(status.code(), source + ":" + std::to_string(c.line) + ": " + status.message());
  }
  document = std::move(working);
  return ScriptResult{static_cast<int>(commands.size())};
}

}  // namespace tessera
