// tessera remote: talk to a tessera-server through the client library --
// list, create, grant, run an edit script, export, stats.
#include <charconv>
#include <cstdio>
#include <map>
#include <fstream>
#include <sstream>

#include "client/cli/arguments.h"
#include "client/cli/commands.h"
#include "client/lib/session.h"
#include "core/document/edit_script.h"
#include "core/util/file_io.h"

namespace tessera::cli {

namespace {

constexpr const char* kHelp =
    "usage: tessera remote [--host H] [--port N] [--token T | --token-file F] [--name NAME] <command>\n"
    "\n"
    "  list                                   documents this token may read\n"
    "  create MESH [--tags FILE] [--max-level N] [--doc-name NAME]\n"
    "                                         import a base mesh as a new document (admin)\n"
    "  grant DOC|all viewer|editor|admin TOKEN   let TOKEN act on a document (admin)\n"
    "  edit DOC --script FILE                 send each script line; waits for every ack\n"
    "  export DOC --level N [--limit] -o OUT.glb\n"
    "  stats                                  the server's counters\n"
    "\n"
    "Scripts use the format of 'tessera doc edit' (move, offset, crease, corner, undo, redo).\n";

int fail(const std::string& what, const std::string& message) {
  std::fprintf(stderr, "tessera remote %s: %s\n", what.c_str(), message.c_str());
  return 1;
}

int usage(const std::string& message) {
  std::fprintf(stderr, "tessera remote: %s\n\n%s", message.c_str(), kHelp);
  return 2;
}

// Ack -> 0; Reject -> its message on stderr.
int outcome(const std::string& what, const Expected<wire::ServerMessage>& reply) {
  if (!reply.isOk()) return fail(what, reply.status().message());
  if (reply->has_reject()) {
    return fail(what, wire::RejectReason_Name(reply->reject().reason()) + ": " + reply->reject().message());
  }
  return 0;
}

Expected<uint64_t> parseDocument(const std::string& text) {
  uint64_t value = 0;
  std::istringstream in(text);
  if (!(in >> value) || !in.eof() || value == 0) return invalidArgument("bad document id '" + text + "'");
  return value;
}

wire::ClientMessage toWire(const ScriptCommand& c, uint64_t doc) {
  using Kind = ScriptCommand::Kind;
  wire::ClientMessage m;
  switch (c.kind) {
    case Kind::kMove:
    case Kind::kOffset: {
      auto* move = m.mutable_move_vertex();
      move->set_document_id(doc);
      for (VertexId v : c.vertices) move->add_vertex_ids(v.packed());
      move->mutable_target()->set_x(c.value[0]);
      move->mutable_target()->set_y(c.value[1]);
      move->mutable_target()->set_z(c.value[2]);
      move->set_mode(c.kind == Kind::kMove ? wire::MOVE_MODE_DIRECT_MANIPULATION : wire::MOVE_MODE_OFFSET);
      break;
    }
    case Kind::kCrease:
      m.mutable_set_edge_sharpness()->set_document_id(doc);
      m.mutable_set_edge_sharpness()->set_edge_id(c.edge.packed());
      m.mutable_set_edge_sharpness()->set_sharpness(c.sharpness);
      break;
    case Kind::kCorner:
      m.mutable_set_vertex_type()->set_document_id(doc);
      m.mutable_set_vertex_type()->set_vertex_id(c.vertices[0].packed());
      m.mutable_set_vertex_type()->set_sharpness(c.sharpness);
      break;
    case Kind::kUndo:
      m.mutable_undo()->set_document_id(doc);
      m.mutable_undo()->set_edit_id(c.edit.value);
      break;
    case Kind::kRedo:
    case Kind::kRemove:
      m.mutable_redo()->set_document_id(doc);
      m.mutable_redo()->set_edit_id(c.edit.value);
      break;
  }
  return m;
}

int runEdit(client::Session& s, const Arguments& args) {
  if (args.positional.size() != 2) return usage("edit expects DOC --script FILE");
  const std::string* script = args.option("--script");
  if (!script) return usage("edit needs --script FILE");
  auto doc = parseDocument(args.positional[1]);
  if (!doc.isOk()) return usage(doc.status().message());
  auto text = readFile(*script);
  if (!text.isOk()) return fail("edit", text.status().message());
  auto commands = parseEditScript(*text, *script);
  if (!commands.isOk()) return fail("edit", commands.status().message());
  wire::ClientMessage open;
  open.mutable_open_document()->set_document_id(*doc);
  if (int rc = outcome("edit", s.call(open, 30))) return rc;
  for (const ScriptCommand& c : *commands) {
    if (c.kind == ScriptCommand::Kind::kRemove) {
      return fail("edit", *script + ":" + std::to_string(c.line) + ": remove is local only (use undo)");
    }
    auto reply = s.call(toWire(c, *doc), 30);
    if (int rc = outcome("edit", reply)) return rc;
    std::printf("%s:%d: version %llu, edit %llu\n", script->c_str(), c.line,
                static_cast<unsigned long long>(reply->ack().version()),
                static_cast<unsigned long long>(reply->ack().edit_id()));
  }
  return 0;
}

}  // namespace

int runRemote(const std::vector<std::string>& rawArgs) {
  ArgumentSpec spec{{"--limit"},
                    {"--host", "--port", "--token", "--token-file", "--name", "--tags", "--max-level", "--doc-name",
                     "--script", "--level", "--output"}};
  auto args = parseArguments(rawArgs, spec);
  if (!args.isOk()) return usage(args.status().message());
  if (args->has("--help") || args->positional.empty()) {
    std::fputs(kHelp, args->has("--help") ? stdout : stderr);
    return args->has("--help") ? 0 : 2;
  }
  client::SessionOptions options;
  if (const std::string* host = args->option("--host")) options.host = *host;
  if (const std::string* port = args->option("--port")) {
    unsigned value = 0;
    auto [end, ec] = std::from_chars(port->data(), port->data() + port->size(), value);
    if (ec != std::errc() || end != port->data() + port->size() || value > 65535) {
      return usage("--port expects 0..65535, got '" + *port + "'");
    }
    options.port = static_cast<uint16_t>(value);
  }
  if (const std::string* token = args->option("--token")) options.token = *token;
  if (const std::string* file = args->option("--token-file")) {
    std::ifstream in(*file);
    std::getline(in, options.token);
    if (options.token.empty()) return fail("", *file + ": no token in the file");
  }
  options.name = args->option("--name") ? *args->option("--name") : "tessera-cli";
  const std::string command = args->positional[0];
  auto session = client::Session::connect(options);
  if (!session.isOk()) return fail(command, session.status().message());
  client::Session& s = **session;

  if (command == "list") {
    wire::ClientMessage m;
    m.mutable_list_documents();
    auto reply = s.call(m, 30);
    if (int rc = outcome(command, reply)) return rc;
    for (const auto& d : reply->document_list().documents()) {
      std::printf("%llu\t%s\tversion %llu\n", static_cast<unsigned long long>(d.document_id()), d.name().c_str(),
                  static_cast<unsigned long long>(d.version()));
    }
    return 0;
  }
  if (command == "create") {
    if (args->positional.size() != 2) return usage("create expects one mesh file");
    const std::string& path = args->positional[1];
    const std::string extension = path.substr(path.find_last_of('.') + 1);
    const std::map<std::string, wire::MeshFormat> formats = {{"obj", wire::MESH_FORMAT_OBJ}, {"off", wire::MESH_FORMAT_OFF},
                                                              {"ply", wire::MESH_FORMAT_PLY}, {"stl", wire::MESH_FORMAT_STL},
                                                              {"glb", wire::MESH_FORMAT_GLB}};
    auto format = formats.find(extension);
    if (format == formats.end()) return usage("create: " + path + " is not .obj, .off, .ply, .stl or .glb");
    wire::ClientMessage m;
    auto* c = m.mutable_create_document();
    c->set_name(args->option("--doc-name") ? *args->option("--doc-name") : path.substr(path.find_last_of('/') + 1));
    auto mesh = readFile(path);
    if (!mesh.isOk()) return fail(command, mesh.status().message());
    c->set_mesh(std::move(*mesh));
    c->set_mesh_format(format->second);
    if (const std::string* tags = args->option("--tags")) {
      auto text = readFile(*tags);
      if (!text.isOk()) return fail(command, text.status().message());
      c->set_tags(std::move(*text));
    }
    if (const std::string* level = args->option("--max-level")) {
      auto parsed = parseLevel("--max-level", *level);
      if (!parsed.isOk()) return usage(parsed.status().message());
      c->set_max_level(static_cast<uint32_t>(*parsed));
    }
    auto reply = s.call(m, 120);
    if (int rc = outcome(command, reply)) return rc;
    std::printf("%llu\n", static_cast<unsigned long long>(reply->ack().document_id()));
    return 0;
  }
  if (command == "grant") {
    if (args->positional.size() != 4) return usage("grant expects DOC|all ROLE TOKEN");
    uint64_t doc = 0;
    if (args->positional[1] != "all") {
      auto parsed = parseDocument(args->positional[1]);
      if (!parsed.isOk()) return usage(parsed.status().message());
      doc = *parsed;
    }
    const std::map<std::string, wire::Role> roles = {{"viewer", wire::ROLE_VIEWER}, {"editor", wire::ROLE_EDITOR}, {"admin", wire::ROLE_ADMIN}};
    auto role = roles.find(args->positional[2]);
    if (role == roles.end()) return usage("grant: role must be viewer, editor or admin");
    wire::ClientMessage m;
    m.mutable_grant_token()->set_document_id(doc);
    m.mutable_grant_token()->set_role(role->second);
    m.mutable_grant_token()->set_token(args->positional[3]);
    return outcome(command, s.call(m, 30));
  }
  if (command == "edit") return runEdit(s, *args);
  if (command == "export") {
    if (args->positional.size() != 2) return usage("export expects one document");
    const std::string* out = args->option("--output");
    const std::string* level = args->option("--level");
    if (!out || !level) return usage("export needs --level N and -o OUT.glb");
    auto doc = parseDocument(args->positional[1]);
    auto parsed = parseLevel("--level", *level);
    if (!doc.isOk() || !parsed.isOk()) return usage("export: bad document or level");
    wire::ClientMessage open;
    open.mutable_open_document()->set_document_id(*doc);
    if (int rc = outcome(command, s.call(open, 30))) return rc;
    wire::ClientMessage m;
    m.mutable_export_document()->set_document_id(*doc);
    m.mutable_export_document()->set_level(static_cast<uint32_t>(*parsed));
    m.mutable_export_document()->set_limit(args->has("--limit"));
    auto reply = s.call(m, 120);
    if (int rc = outcome(command, reply)) return rc;
    std::ofstream(*out, std::ios::binary) << reply->export_result().glb();
    std::printf("wrote %s (version %llu)\n", out->c_str(), static_cast<unsigned long long>(reply->export_result().version()));
    return 0;
  }
  if (command == "stats") {
    wire::ClientMessage m;
    m.mutable_stats();
    auto reply = s.call(m, 30);
    if (int rc = outcome(command, reply)) return rc;
    for (const auto& stat : reply->stats_reply().stats()) std::printf("%-24s %g\n", stat.name().c_str(), stat.value());
    return 0;
  }
  return usage("unknown remote command '" + command + "'");
}

}  // namespace tessera::cli
