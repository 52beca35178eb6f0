// A new document's base mesh, as a client sends it in CreateDocument: the
// bytes imported in memory (never through the filesystem) with the import
// options of `tessera doc new`, its tags applied, and the document built at
// the requested level (docs/PROTOCOL.md §13, import options).
#pragma once

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/util/status.h"
#include "protocol/tessera.pb.h"

namespace tessera::server {

// Errors name the file as the client named it (file_name), else the
// document: "cube.obj:12: ...", never a server path. `maxLevel` is the
// server's limit; `report` tells what the import dropped and creased.
Expected<Document> importDocument(const wire::CreateDocument& request, int maxLevel, ImportReport& report);

}  // namespace tessera::server
