#include "client/replay/script.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "core/hierarchy/ids.h"

namespace tessera::replay {

namespace {

using nlohmann::json;

// Every accessor returns a message (empty when fine) so that the caller can
// prefix "FILE:LINE: ".
std::string requireKeys(const json& j, std::initializer_list<const char*> allowed) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool known = false;
    for (const char* k : allowed) known = known || it.key() == k;
    if (!known) return "unknown key \"" + it.key() + "\"";
  }
  return "";
}

std::string getVertex(const json& j, const char* key, uint64_t& out) {
  if (!j.contains(key) || !j[key].is_string())
    return std::string("\"") + key + "\" must be a vertex id string like \"v2:40\"";
  auto id = parseVertexId(j[key].get<std::string>());
  if (!id.isOk()) return id.status().message();
  out = id->packed();
  return "";
}

std::string getSharpness(const json& j, float& out) {
  if (!j.contains("sharpness")) return "\"sharpness\" is missing";
  const json& s = j["sharpness"];
  if (s.is_string() && s.get<std::string>() == "inf") {
    out = INFINITY;
    return "";
  }
  if (!s.is_number()) return "\"sharpness\" must be a number or \"inf\"";
  const double v = s.get<double>();
  if (!std::isfinite(v) || v < 0) return "\"sharpness\" must be >= 0";
  out = static_cast<float>(v);
  return "";
}

std::string parseCommand(const json& j, ScriptCommand& c) {
  if (!j.is_object()) return "a command must be a JSON object";
  if (!j.contains("t") || !j["t"].is_number_integer() || j["t"].get<int64_t>() < 0) {
    return "\"t\" must be a non-negative integer (milliseconds)";
  }
  c.timeMs = j["t"].get<int64_t>();
  if (!j.contains("actor") || !j["actor"].is_string() || j["actor"].get<std::string>().empty()) {
    return "\"actor\" must be a non-empty string";
  }
  c.actor = j["actor"].get<std::string>();
  if (c.actor.size() > 100) return "\"actor\" is longer than 100 bytes";
  if (!j.contains("cmd") || !j["cmd"].is_string())
    return "\"cmd\" must be one of move, crease, corner, interpolate, undo, redo";
  const std::string cmd = j["cmd"].get<std::string>();
  if (cmd == "move") {
    c.kind = ScriptCommand::Kind::kMove;
    if (auto e = requireKeys(j, {"t", "actor", "cmd", "vertex", "mode", "to"}); !e.empty()) return e;
    const json& v = j.contains("vertex") ? j["vertex"] : json();
    std::vector<json> ids = v.is_array() ? v.get<std::vector<json>>() : std::vector<json>{v};
    if (ids.empty()) return "\"vertex\" is an empty list";
    for (const json& id : ids) {
      uint64_t packed = 0;
      if (auto e = getVertex(json{{"vertex", id}}, "vertex", packed); !e.empty()) return e;
      c.vertices.push_back(packed);
    }
    const std::string mode = j.contains("mode") && j["mode"].is_string() ? j["mode"].get<std::string>() : "";
    if (mode != "offset" && mode != "direct") return "\"mode\" must be \"offset\" or \"direct\"";
    c.offset = mode == "offset";
    if (!j.contains("to") || !j["to"].is_array() || j["to"].size() != 3) return "\"to\" must be [x, y, z]";
    for (int i = 0; i < 3; ++i) {
      if (!j["to"][i].is_number()) return "\"to\" must hold three numbers";
      c.to[i] = j["to"][i].get<double>();
      if (!std::isfinite(c.to[i])) return "\"to\" must be finite";
    }
  } else if (cmd == "crease") {
    c.kind = ScriptCommand::Kind::kCrease;
    if (auto e = requireKeys(j, {"t", "actor", "cmd", "edge", "sharpness"}); !e.empty()) return e;
    if (!j.contains("edge") || !j["edge"].is_string())
      return "\"edge\" must be an edge id string like \"e1:5\"";
    auto id = parseEdgeId(j["edge"].get<std::string>());
    if (!id.isOk()) return id.status().message();
    c.edge = id->packed();
    if (auto e = getSharpness(j, c.sharpness); !e.empty()) return e;
  } else if (cmd == "corner") {
    c.kind = ScriptCommand::Kind::kCorner;
    if (auto e = requireKeys(j, {"t", "actor", "cmd", "vertex", "sharpness"}); !e.empty()) return e;
    uint64_t packed = 0;
    if (auto e = getVertex(j, "vertex", packed); !e.empty()) return e;
    c.vertices.push_back(packed);
    if (auto e = getSharpness(j, c.sharpness); !e.empty()) return e;
  } else if (cmd == "interpolate") {
    c.kind = ScriptCommand::Kind::kInterpolate;
    if (auto e = requireKeys(j, {"t", "actor", "cmd", "vertex", "on", "tension"}); !e.empty()) return e;
    uint64_t packed = 0;
    if (auto e = getVertex(j, "vertex", packed); !e.empty()) return e;
    c.vertices.push_back(packed);
    if (!j.contains("on") || !j["on"].is_boolean()) return "\"on\" must be true or false";
    c.interpolating = j["on"].get<bool>();
    if (!j.contains("tension") || !j["tension"].is_number()) return "\"tension\" must be a number";
    c.tension = j["tension"].get<double>();
    if (!std::isfinite(c.tension)) return "\"tension\" must be finite";
  } else if (cmd == "undo" || cmd == "redo") {
    c.kind = cmd == "undo" ? ScriptCommand::Kind::kUndo : ScriptCommand::Kind::kRedo;
    if (auto e = requireKeys(j, {"t", "actor", "cmd", "edit"}); !e.empty()) return e;
    if (!j.contains("edit") || !j["edit"].is_number_integer() || j["edit"].get<int64_t>() == 0) {
      return "\"edit\" must be an edit id (> 0) or a step back through the actor's edits (< 0)";
    }
    c.edit = j["edit"].get<int64_t>();
  } else {
    return "unknown cmd \"" + cmd + "\" (expected move, crease, corner, interpolate, undo, redo)";
  }
  return "";
}

std::string parseHeader(const json& j, ScriptHeader& h) {
  if (!j.is_object() || !j.contains("format") || j["format"] != "tessera-replay") {
    return "the first line must be a header {\"format\":\"tessera-replay\",\"version\":1,...}";
  }
  if (auto e = requireKeys(j, {"format", "version", "document", "profile", "generator"}); !e.empty())
    return e;
  if (!j.contains("version") || !j["version"].is_number_integer())
    return "the header has no integer \"version\"";
  if (j["version"].get<int64_t>() != kScriptVersion) {
    return "script version " + j["version"].dump() + " is not supported (this build reads version 1)";
  }
  if (j.contains("document")) {
    if (!j["document"].is_number_unsigned()) return "\"document\" must be a positive integer";
    h.document = j["document"].get<uint64_t>();
  }
  if (j.contains("profile")) {
    const json& p = j["profile"];
    if (!p.is_array() || p.size() != 3 || !p[0].is_number_unsigned() || !p[1].is_number_unsigned() ||
        !p[2].is_number()) {
      return "\"profile\" must be [base_level, max_level, angle_degrees]";
    }
    h.baseLevel = p[0].get<uint32_t>();
    h.maxLevel = p[1].get<uint32_t>();
    h.angleDegrees = p[2].get<double>();
  }
  if (j.contains("generator")) {
    if (!j["generator"].is_string()) return "\"generator\" must be a string";
    h.generator = j["generator"].get<std::string>();
  }
  return "";
}

}  // namespace

Expected<Script> parseScript(const std::string& text, const std::string& source) {
  Script script;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  bool sawHeader = false;
  auto fail = [&](const std::string& reason) {
    return parseError(source + ":" + std::to_string(number) + ": " + reason);
  };
  while (std::getline(in, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    json j = json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded()) return fail("not valid JSON");
    if (!sawHeader) {
      if (auto e = parseHeader(j, script.header); !e.empty()) return fail(e);
      sawHeader = true;
      continue;
    }
    ScriptCommand c;
    c.line = number;
    if (auto e = parseCommand(j, c); !e.empty()) return fail(e);
    if (!script.commands.empty() && c.timeMs < script.commands.back().timeMs) {
      return fail("\"t\" " + std::to_string(c.timeMs) + " is before the previous line's " +
                  std::to_string(script.commands.back().timeMs));
    }
    script.commands.push_back(std::move(c));
  }
  if (!sawHeader) return parseError(source + ": empty script (no header line)");
  return script;
}

Expected<Script> readScript(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return ioError(path + ": cannot open");
  std::stringstream ss;
  ss << in.rdbuf();
  return parseScript(ss.str(), path);
}

std::string headerLine(const ScriptHeader& h) {
  nlohmann::ordered_json j = {{"format", "tessera-replay"}, {"version", kScriptVersion}};
  if (h.document != 0) j["document"] = h.document;
  j["profile"] = {h.baseLevel, h.maxLevel, h.angleDegrees};
  if (!h.generator.empty()) j["generator"] = h.generator;
  return j.dump();
}

std::string commandLine(const ScriptCommand& c) {
  nlohmann::ordered_json j = {{"t", c.timeMs}, {"actor", c.actor}};
  auto sharp = [](float s) {
    return std::isinf(s) ? nlohmann::ordered_json("inf") : nlohmann::ordered_json(s);
  };
  switch (c.kind) {
    case ScriptCommand::Kind::kMove: {
      j["cmd"] = "move";
      std::vector<std::string> ids;
      for (uint64_t v : c.vertices) ids.push_back(VertexId::fromPacked(v).toString());
      j["vertex"] = ids.size() == 1 ? nlohmann::ordered_json(ids[0]) : nlohmann::ordered_json(ids);
      j["mode"] = c.offset ? "offset" : "direct";
      j["to"] = {c.to[0], c.to[1], c.to[2]};
      break;
    }
    case ScriptCommand::Kind::kCrease:
      j["cmd"] = "crease";
      j["edge"] = EdgeId::fromPacked(c.edge).toString();
      j["sharpness"] = sharp(c.sharpness);
      break;
    case ScriptCommand::Kind::kCorner:
      j["cmd"] = "corner";
      j["vertex"] = VertexId::fromPacked(c.vertices.at(0)).toString();
      j["sharpness"] = sharp(c.sharpness);
      break;
    case ScriptCommand::Kind::kInterpolate:
      j["cmd"] = "interpolate";
      j["vertex"] = VertexId::fromPacked(c.vertices.at(0)).toString();
      j["on"] = c.interpolating;
      j["tension"] = c.tension;
      break;
    case ScriptCommand::Kind::kUndo:
    case ScriptCommand::Kind::kRedo:
      j["cmd"] = c.kind == ScriptCommand::Kind::kUndo ? "undo" : "redo";
      j["edit"] = c.edit;
      break;
  }
  return j.dump();
}

wire::ClientMessage toWire(const ScriptCommand& c, uint64_t doc, uint64_t editId) {
  wire::ClientMessage m;
  switch (c.kind) {
    case ScriptCommand::Kind::kMove: {
      auto* move = m.mutable_move_vertex();
      move->set_document_id(doc);
      for (uint64_t v : c.vertices) move->add_vertex_ids(v);
      move->mutable_target()->set_x(c.to[0]);
      move->mutable_target()->set_y(c.to[1]);
      move->mutable_target()->set_z(c.to[2]);
      move->set_mode(c.offset ? wire::MOVE_MODE_OFFSET : wire::MOVE_MODE_DIRECT_MANIPULATION);
      break;
    }
    case ScriptCommand::Kind::kCrease:
      m.mutable_set_edge_sharpness()->set_document_id(doc);
      m.mutable_set_edge_sharpness()->set_edge_id(c.edge);
      m.mutable_set_edge_sharpness()->set_sharpness(c.sharpness);
      break;
    case ScriptCommand::Kind::kCorner:
      m.mutable_set_vertex_type()->set_document_id(doc);
      m.mutable_set_vertex_type()->set_vertex_id(c.vertices.at(0));
      m.mutable_set_vertex_type()->set_sharpness(c.sharpness);
      break;
    case ScriptCommand::Kind::kInterpolate:
      m.mutable_set_interpolation()->set_document_id(doc);
      m.mutable_set_interpolation()->set_vertex_id(c.vertices.at(0));
      m.mutable_set_interpolation()->set_interpolating(c.interpolating);
      m.mutable_set_interpolation()->set_tension(c.tension);
      break;
    case ScriptCommand::Kind::kUndo:
      m.mutable_undo()->set_document_id(doc);
      m.mutable_undo()->set_edit_id(editId);
      break;
    case ScriptCommand::Kind::kRedo:
      m.mutable_redo()->set_document_id(doc);
      m.mutable_redo()->set_edit_id(editId);
      break;
  }
  return m;
}

Script generateScript(const GenerateOptions& o) {
  Script script;
  script.header.document = o.document;
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<uint64_t> vertex(0, o.vertexCount == 0 ? 0 : o.vertexCount - 1);
  const double periodMs = 1000.0 / std::max(o.rate, 1e-3);
  const int64_t perEditor = static_cast<int64_t>(std::floor(o.seconds * o.rate));
  struct Pending {
    int64_t t;
    int editor;
  };
  std::vector<Pending> all;
  for (int e = 0; e < o.editors; ++e) {
    // Stagger the editors evenly inside one period.
    for (int64_t i = 0; i < perEditor; ++i) {
      all.push_back(
          {static_cast<int64_t>(std::llround((i + static_cast<double>(e) / o.editors) * periodMs)), e});
    }
  }
  std::stable_sort(all.begin(), all.end(), [](const Pending& a, const Pending& b) { return a.t < b.t; });
  std::vector<int> last(o.editors, 0);  // 0 nothing, 1 move, 2 undo
  for (const Pending& p : all) {
    ScriptCommand c;
    c.timeMs = p.t;
    c.actor = "editor-" + std::to_string(p.editor + 1);
    const double roll = (unit(rng) + 1) / 2;
    if (o.undo && last[p.editor] == 1 && roll < 0.1) {
      c.kind = ScriptCommand::Kind::kUndo;
      c.edit = -1;
      last[p.editor] = 2;
    } else if (o.undo && last[p.editor] == 2 && roll < 0.5) {
      c.kind = ScriptCommand::Kind::kRedo;
      c.edit = -1;
      last[p.editor] = 1;
    } else {
      c.kind = ScriptCommand::Kind::kMove;
      c.offset = true;
      c.vertices.push_back(VertexId(o.vertexLevel, vertex(rng)).packed());
      for (double& x : c.to) x = std::round(unit(rng) * o.step * 1e6) / 1e6;
      last[p.editor] = 1;
    }
    script.commands.push_back(std::move(c));
  }
  return script;
}

}  // namespace tessera::replay
