// tessera: the command-line tool (CLI11). Subcommands: info, refine, doc,
// remote, morph. Usage errors print the message naming the option and exit 2;
// --help and --version exit 0; a command's own failure exits 1.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "client/cli/commands.h"
#include "tessera/version.h"

namespace {

using tessera::cli::Action;

// "info", "doc new", "remote edit": the subcommands chosen so far.
std::string chosenPath(const CLI::App& app) {
  std::string path;
  for (const CLI::App* at = &app;;) {
    const auto chosen = at->get_subcommands();
    if (chosen.empty()) return path;
    at = chosen.front();
    path += (path.empty() ? "" : " ") + at->get_name();
  }
}

// The first word that should name a subcommand and does not ("frob" in
// "tessera remote --port 1 frob"), or "": CLI11 would only say "a
// subcommand is required". Skips the values of options that take one.
std::string unknownCommand(CLI::App& app, int argc, char** argv) {
  CLI::App* at = &app;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    const auto commands = at->get_subcommands([](CLI::App*) { return true; });
    if (commands.empty()) return "";
    if (word == "--") return "";
    if (word.size() > 1 && word[0] == '-') {
      const CLI::Option* option = at->get_option_no_throw(word.substr(0, word.find('=')));
      if (option != nullptr && option->get_items_expected_min() > 0 && word.find('=') == std::string::npos)
        ++i;
      continue;
    }
    CLI::App* next = nullptr;
    for (CLI::App* sub : commands) next = sub->check_name(word) ? sub : next;
    if (next == nullptr) return word;
    at = next;
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("tessera: hierarchical Loop subdivision surfaces from the command line", "tessera");
  app.set_version_flag("--version", std::string("tessera ") + tessera::kVersion,
                       "print the version and exit");
  app.require_subcommand(1);
  Action action;
  tessera::cli::addInfoCommand(app, action);
  tessera::cli::addRefineCommand(app, action);
  tessera::cli::addDocCommand(app, action);
  tessera::cli::addRemoteCommand(app, action);
  tessera::cli::addMorphCommand(app, action);
  app.footer("Run 'tessera <command> --help' for the options of a command.");  // after: not inherited

  if (argc < 2) {
    std::fputs(app.help().c_str(), stderr);
    return tessera::cli::kExitUsage;
  }
  if (const std::string unknown = unknownCommand(app, argc, argv); !unknown.empty()) {
    std::fprintf(stderr, "tessera: unknown command '%s'\nRun 'tessera --help' for the commands.\n",
                 unknown.c_str());
    return tessera::cli::kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);  // the help of the subcommand asked, alone
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const std::string path = chosenPath(app);
    std::fprintf(stderr, "tessera%s%s: %s\nRun 'tessera%s%s --help' for its options.\n",
                 path.empty() ? "" : " ", path.c_str(), e.what(), path.empty() ? "" : " ", path.c_str());
    return tessera::cli::kExitUsage;
  }
  if (!action) {
    std::fputs(app.help().c_str(), stderr);
    return tessera::cli::kExitUsage;
  }
  // Errors exit with a message, never by a signal or an escaped exception.
  try {
    return action();
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "tessera %s: out of memory (try a lower --level)\n", chosenPath(app).c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessera %s: internal error: %s\n", chosenPath(app).c_str(), e.what());
  }
  return tessera::cli::kExitFailure;
}
