// tessera-server's subcommands for operators (docs/OPERATIONS.md): each
// prints its result on stdout and errors as JSON log lines, and returns
// the process exit code.
#pragma once

#include "server/app/command_line.h"

namespace tessera::server {

int runTokenNew(const ServerCommandLine& command);  // prints the token, stores its hash
int runBackup(const ServerCommandLine& command);
int runRestore(const ServerCommandLine& command);
int runHealth(const ServerCommandLine& command);  // 0 healthy, 1 not

}  // namespace tessera::server
