// tessera: the command-line tool. Subcommands: info, refine.
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "client/cli/commands.h"

namespace {

constexpr const char* kUsage =
    "usage: tessera <command> [options]\n"
    "\n"
    "commands:\n"
    "  info    IN [--tags FILE] [--triangulate]      describe a base mesh\n"
    "  refine  IN --level N [--limit] [--tags FILE]  Loop-refine with sharp features\n"
    "          [--triangulate] [--draco] -o OUT       and write .obj, .ply or .glb\n"
    "  doc     new | edit | info | export          hierarchical documents with edits at any level\n"
    "  remote  list | create | grant | edit | export | stats   talk to a tessera-server\n"
    "\n"
    "Run 'tessera <command> --help' for the options of a command.\n";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::fputs(kUsage, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  // Errors exit with a message, never by a signal or an escaped exception.
  try {
    if (command == "info") return tessera::cli::runInfo(args);
    if (command == "refine") return tessera::cli::runRefine(args);
    if (command == "doc") return tessera::cli::runDoc(args);
    if (command == "remote") return tessera::cli::runRemote(args);
    std::fprintf(stderr, "tessera: unknown command '%s'\n\n%s", command.c_str(), kUsage);
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "tessera %s: out of memory (try a lower --level)\n", command.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessera %s: internal error: %s\n", command.c_str(), e.what());
  }
  return 1;
}
