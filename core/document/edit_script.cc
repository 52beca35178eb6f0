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
Status parseMove(const std::vector<std::string>& t, const char* keyword, std::vector<VertexId>& ids, Vec3& value) {
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

Status applyLine(const std::vector<std::string>& t, Document& doc) {
  const std::string& cmd = t[0];
  if (cmd == "move" || cmd == "offset") {
    std::vector<VertexId> ids;
    Vec3 value;
    TESSERA_RETURN_IF_ERROR(parseMove(t, cmd == "move" ? "to" : "by", ids, value));
    auto id = cmd == "move" ? doc.moveToLimit(ids, value) : doc.moveBy(ids, value);
    return id.status();
  }
  if (cmd == "crease" || cmd == "corner") {
    if (t.size() != 3) return parseError("expected '" + cmd + " ID SHARPNESS'");
    float s = 0;
    if (!parseSharpness(t[2], s)) return parseError("bad sharpness '" + t[2] + "'");
    if (cmd == "crease") {
      TESSERA_ASSIGN_OR_RETURN(EdgeId edge, parseEdgeId(t[1]));
      return doc.setEdgeSharpness(edge, s).status();
    }
    TESSERA_ASSIGN_OR_RETURN(VertexId vertex, parseVertexId(t[1]));
    return doc.setVertexSharpness(vertex, s).status();
  }
  if (cmd == "undo" || cmd == "redo" || cmd == "remove") {
    if (t.size() != 2) return parseError("expected '" + cmd + " EDIT'");
    TESSERA_ASSIGN_OR_RETURN(EditId id, parseEditId(t[1]));
    return cmd == "undo" ? doc.undo(id) : cmd == "redo" ? doc.redo(id) : doc.remove(id);
  }
  return parseError("unknown command '" + cmd + "' (move, offset, crease, corner, undo, redo, remove)");
}

}  // namespace

Expected<ScriptResult> applyEditScript(const std::string& text, const std::string& source, Document& document) {
  Document working = document;  // all or nothing
  ScriptResult result;
  std::istringstream in(text);
  std::string line;
  int lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const std::vector<std::string> tokens = splitTokens(line);
    if (tokens.empty()) continue;
    Status status = applyLine(tokens, working);
    if (!status.isOk()) return Status(status.code(), source + ":" + std::to_string(lineNumber) + ": " + status.message());
    ++result.commands;
  }
  document = std::move(working);
  return result;
}

}  // namespace tessera
