// tessera-server: see server.h and docs/PROTOCOL.md.
#include <cstdio>
#include <string>
#include <vector>

#include "server/config.h"
#include "server/log.h"
#include "server/server.h"

int main(int argc, char** argv) {
  using namespace tessera::server;
  std::vector<std::string> args(argv + 1, argv + argc);
  for (const std::string& a : args) {
    if (a == "--help" || a == "-h") {
      std::fputs(kServerUsage, stdout);
      return 0;
    }
  }
  auto config = parseServerArguments(args);
  if (!config.isOk()) {
    std::fprintf(stderr, "tessera-server: %s\n\n%s", config.status().message().c_str(), kServerUsage);
    return 2;
  }
  if (config->verbose) setLogLevel(LogLevel::kDebug);
  auto server = Server::create(*config);
  if (!server.isOk()) {
    std::fprintf(stderr, "tessera-server: %s\n", server.status().toString().c_str());
    return 1;
  }
  (*server)->run();
  return 0;
}
