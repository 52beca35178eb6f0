// The `tessera` subcommands, registered on the CLI11 application. Each one
// sets `action` when it is the subcommand chosen; the action returns the
// process exit code and prints errors as "tessera <command>: <message>".
#pragma once

#include <CLI/CLI.hpp>

#include "client/cli/command_line.h"

namespace tessera::cli {

void addInfoCommand(CLI::App& app, Action& action);
void addRefineCommand(CLI::App& app, Action& action);
void addDocCommand(CLI::App& app, Action& action);     // doc new | edit | info | export
void addRemoteCommand(CLI::App& app, Action& action);  // remote list | create | grant | edit | export | stats
void addMorphCommand(CLI::App& app, Action& action);   // the image morph (docs/INTERPOLATION.md)

}  // namespace tessera::cli
