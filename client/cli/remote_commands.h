// The `tessera remote` subcommands with files of their own.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>

#include "client/cli/command_line.h"
#include "client/cli/remote_session.h"

namespace tessera::cli {

// remote create MESH [--tags FILE] [--triangulate] [--drop-unused] [--crease-angle DEG]
//                    [--max-level N] [--crease-method M]
//                    [--boundary B] [--doc-name NAME]
void addRemoteCreate(CLI::App& remote, std::shared_ptr<ConnectionArgs> connection, Action& action);
// remote edit DOC --script FILE: one EditBatch, all or nothing.
void addRemoteEdit(CLI::App& remote, std::shared_ptr<ConnectionArgs> connection, Action& action);
// remote morph-key DOC MESH [--images A.png B.png]: the second key (AddMorphKey).
void addRemoteMorphKey(CLI::App& remote, std::shared_ptr<ConnectionArgs> connection, Action& action);
// remote cage DOC [--level N] [--list]: one level's polygons (GetCage).
void addRemoteCage(CLI::App& remote, std::shared_ptr<ConnectionArgs> connection, Action& action);

}  // namespace tessera::cli
