// tessera-server: serves documents (server.h, docs/PROTOCOL.md), or runs an
// operator subcommand (operator_commands.h, docs/OPERATIONS.md). Every line
// it logs, start-up errors included, is one JSON object.
#include <cstdio>
#include <string>
#include <vector>

#include "core/util/heap_policy.h"
#include "server/app/command_line.h"
#include "server/app/operator_commands.h"
#include "server/app/server.h"
#include "server/base/log.h"

int main(int argc, char** argv) {
  using namespace tessera::server;
  const ParsedCommandLine parsed = parseServerCommandLine(std::vector<std::string>(argv + 1, argv + argc));
  if (parsed.stop) {
    if (!parsed.error.empty()) {
      logEvent(LogLevel::kError, "usage", {{"error", parsed.error}, {"help", "tessera-server --help"}});
    }
    std::fputs(parsed.output.c_str(), stdout);
    return parsed.exitCode;
  }
  const ServerCommandLine& command = parsed.command;
  const ServerConfig& config = command.config;
  if (config.verbose) setLogLevel(LogLevel::kDebug);
  if (!config.logFile.empty()) {
    if (auto opened = setLogFile(config.logFile); !opened.isOk()) {
      logEvent(LogLevel::kError, "startup_failed", {{"error", opened.message()}});
      return 1;
    }
  }
  switch (command.action) {
    case ServerAction::kTokenNew:
      return runTokenNew(command);
    case ServerAction::kBackup:
      return runBackup(command);
    case ServerAction::kRestore:
      return runRestore(command);
    case ServerAction::kHealth:
      return runHealth(command);
    case ServerAction::kServe:
      break;
  }
  // Levels are rebuilt and grown over and over: freed memory stays for reuse
  // rather than being faulted in again, and the bulk work trims the heap
  // (core/util/heap_policy.h).
  if (!tessera::keepFreedMemoryForReuse()) logEvent(LogLevel::kWarn, "heap_policy_refused", {});
  auto server = Server::create(config);
  if (!server.isOk()) {
    logEvent(LogLevel::kError, "startup_failed", {{"error", server.status().toString()}});
    return 1;
  }
  (*server)->run();
  return 0;
}
