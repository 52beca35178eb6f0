// The `tessera` subcommands. Each returns the process exit code and prints
// errors as "tessera <command>: <message>" on stderr.
#pragma once

#include <string>
#include <vector>

namespace tessera::cli {

int runInfo(const std::vector<std::string>& args);
int runRefine(const std::vector<std::string>& args);
int runDoc(const std::vector<std::string>& args);
int runRemote(const std::vector<std::string>& args);

}  // namespace tessera::cli
