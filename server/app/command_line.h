// tessera-server's command line (CLI11): serving options, readable from a
// configuration file with --config, and the operator subcommands. Every
// option is listed once, here; docs/OPERATIONS.md and
// deploy/tessera-server.conf describe the same set.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "server/base/config.h"

namespace tessera::server {

enum class ServerAction {
  kServe,     // no subcommand
  kTokenNew,  // token new: print a new random token, store its hash
  kBackup,    // backup --to FILE: online copy of the store
  kRestore,   // restore --from FILE: replace a stopped server's store
  kHealth,    // health [--url U]: ask a running server's /healthz
};

struct ServerCommandLine {
  ServerAction action = ServerAction::kServe;
  ServerConfig config;
  std::string role = "editor";  // token new
  uint64_t documentId = 0;      // token new: 0 = every document
  std::string path;             // backup --to, restore --from
  std::string url;              // health
};

// What parsing decided: run `command`, or stop with `exitCode` after
// printing `output` (help and version on stdout, exit 0) or after a usage
// error (`error` names the option; exit 2).
struct ParsedCommandLine {
  ServerCommandLine command;
  bool stop = false;
  int exitCode = 0;
  std::string output;
  std::string error;
};

ParsedCommandLine parseServerCommandLine(const std::vector<std::string>& args);

}  // namespace tessera::server
