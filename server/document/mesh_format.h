// The file extension the importer reads a wire MeshFormat as (".obj", ...),
// or nullptr for an unset or unknown format.
#pragma once

#include "protocol/tessera.pb.h"

namespace tessera::server {

const char* meshExtensionOf(wire::MeshFormat format);

}  // namespace tessera::server
