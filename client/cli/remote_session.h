// What the `tessera remote` subcommands share: the connection options, a
// connection that explains its failures (a refused token, an unreachable
// server), and how a reply becomes an exit code.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "client/cli/command_line.h"
#include "client/lib/session.h"
#include "core/util/status.h"

namespace tessera::cli {

struct ConnectionArgs {
  std::string host = "127.0.0.1";
  int port = 7878;
  std::string token, tokenFile;
  std::string name = "tessera-cli";
  bool tls = false;
  std::string tlsCaFile;
};

// --host, --port, --token, --token-file, --name, --tls, --tls-ca.
void addConnectionOptions(CLI::App& app, ConnectionArgs& args);

// A session, or a message for people: "authentication failed: ..." for a
// token the server does not know, "cannot reach tessera-server at H:P: ..."
// when nothing answers. Errors of the token file are usage errors
// (kInvalidArgument).
Expected<std::unique_ptr<client::Session>> connectTo(const ConnectionArgs& args);

// Prints a failed connection as "tessera remote <command>: <message>" and
// returns the exit code (kExitUsage for a bad token file, else kExitFailure).
int connectFailed(const std::string& command, const Status& status);

// An Ack -> 0; a Reject or a failed call -> its message on stderr, 1.
int outcome(const std::string& command, const Expected<wire::ServerMessage>& reply);

// A session with document `doc` open for `tessera remote <command>`, or,
// with no session, the exit code of what failed, its reason already
// printed (connectFailed, outcome).
struct OpenedDocument {
  std::unique_ptr<client::Session> session;
  int exitCode = 0;
};
OpenedDocument openDocument(const ConnectionArgs& args, const std::string& command, uint64_t doc);

// A document id as the user typed it: a whole number > 0.
Expected<uint64_t> parseDocumentId(const std::string& text);

// The wire format of a mesh file, from its extension (.obj, .off, .ply,
// .stl, .glb); an error naming the file otherwise.
Expected<wire::MeshFormat> meshFormatOf(const std::string& path);

}  // namespace tessera::cli
