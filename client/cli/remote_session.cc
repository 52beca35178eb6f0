#include "client/cli/remote_session.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace tessera::cli {

void addConnectionOptions(CLI::App& app, ConnectionArgs& args) {
  const char* group = "Connection (before or after the command)";
  app.add_option("--host", args.host, "the server's address (default 127.0.0.1)")->group(group);
  app.add_option("--port", args.port, "the server's port (default 7878)")
      ->check(CLI::Range(1, 65535))
      ->group(group);
  app.add_option("--token", args.token, "access token")->group(group);
  app.add_option("--token-file", args.tokenFile, "read the access token from the first line of FILE")
      ->type_name("FILE")
      ->group(group);
  app.add_option("--name", args.name, "how others see this session (default tessera-cli)")->group(group);
  app.add_flag("--tls", args.tls, "connect with TLS, verifying the server's certificate and name")
      ->group(group);
  app.add_option("--tls-ca", args.tlsCaFile, "trusted certificates (PEM) for --tls; default: the system's")
      ->type_name("FILE")
      ->group(group);
}

Expected<std::unique_ptr<client::Session>> connectTo(const ConnectionArgs& args) {
  client::SessionOptions options;
  options.host = args.host;
  options.port = static_cast<uint16_t>(args.port);
  options.name = args.name;
  options.tls = args.tls || !args.tlsCaFile.empty();
  options.tlsCaFile = args.tlsCaFile;
  options.token = args.token;
  if (!args.tokenFile.empty()) {
    if (!args.token.empty()) return invalidArgument("--token and --token-file: give one of them");
    std::ifstream in(args.tokenFile);
    if (!in) return invalidArgument("--token-file " + args.tokenFile + ": cannot open it");
    std::getline(in, options.token);
    while (!options.token.empty() && (options.token.back() == '\r' || options.token.back() == ' ')) {
      options.token.pop_back();
    }
    if (options.token.empty())
      return invalidArgument("--token-file " + args.tokenFile + ": no token in its first line");
  }
  wire::ErrorCode refusal = wire::ERROR_CODE_UNSPECIFIED;
  auto session = client::Session::connect(options, &refusal);
  if (session.isOk()) return session;
  const std::string where = args.host + ":" + std::to_string(args.port);
  if (refusal == wire::ERROR_CODE_AUTH_FAILED) {
    return Status(ErrorCode::kNotFound,
                  "authentication failed: tessera-server at " + where + " does not know this token (" +
                      (args.tokenFile.empty() ? std::string("--token") : "--token-file " + args.tokenFile) +
                      "); ask its admin for one (tessera-server token new)");
  }
  if (refusal != wire::ERROR_CODE_UNSPECIFIED) {
    return Status(session.status().code(), "tessera-server at " + where + " " + session.status().message());
  }
  if (isTransient(session.status())) {
    return Status(ErrorCode::kIoError, "cannot reach tessera-server at " + where + ": " +
                                           session.status().message() +
                                           " (is it running? see --host and --port)");
  }
  return session.status();
}

int connectFailed(const std::string& command, const Status& status) {
  fail("remote " + command, status.message());
  return status.code() == ErrorCode::kInvalidArgument ? kExitUsage : kExitFailure;
}

int outcome(const std::string& command, const Expected<wire::ServerMessage>& reply) {
  if (!reply.isOk()) return fail("remote " + command, reply.status().message());
  if (reply->has_reject()) {
    // A wrong token is refused at the handshake; a session that reaches a
    // command unauthenticated connected without one.
    const bool noToken = reply->reject().reason() == wire::REJECT_REASON_NOT_AUTHENTICATED;
    return fail(
        "remote " + command,
        wire::RejectReason_Name(reply->reject().reason()) + ": " + reply->reject().message() +
            (noToken ? " (no token was given: give --token or --token-file; the server's admin makes one "
                       "with tessera-server token new)"
                     : ""));
  }
  if (reply->has_error()) {
    return fail("remote " + command,
                wire::ErrorCode_Name(reply->error().code()) + ": " + reply->error().message());
  }
  return 0;
}

OpenedDocument openDocument(const ConnectionArgs& args, const std::string& command, uint64_t doc) {
  auto session = connectTo(args);
  if (!session.isOk()) return {nullptr, connectFailed(command, session.status())};
  wire::ClientMessage open;
  open.mutable_open_document()->set_document_id(doc);
  if (int rc = outcome(command, (*session)->call(open, 30))) return {nullptr, rc};
  return {std::move(*session), 0};
}

Expected<uint64_t> parseDocumentId(const std::string& text) {
  uint64_t value = 0;
  std::istringstream in(text);
  if (text.empty() || text[0] == '-' || !(in >> value) || !in.eof() || value == 0) {
    return invalidArgument("DOC expects a document id (a whole number > 0), got '" + text + "'");
  }
  return value;
}

Expected<wire::MeshFormat> meshFormatOf(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  const std::map<std::string, wire::MeshFormat> formats = {
      {".obj", wire::MESH_FORMAT_OBJ}, {".off", wire::MESH_FORMAT_OFF}, {".ply", wire::MESH_FORMAT_PLY},
      {".stl", wire::MESH_FORMAT_STL}, {".glb", wire::MESH_FORMAT_GLB}, {".usda", wire::MESH_FORMAT_USDA}};
  auto format = formats.find(ext);
  if (format != formats.end()) return format->second;
  if (ext == ".gltf")
    return invalidArgument(path + ": send glTF as a .glb (a .gltf may name files beside it)");
  return invalidArgument(path + ": not .obj, .off, .ply, .stl, .glb or .usda");
}

}  // namespace tessera::cli
