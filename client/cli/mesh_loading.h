// Loading the input of a subcommand: the mesh, then its tag file.
#pragma once

#include <string>

#include "core/mesh/base_mesh.h"
#include "core/util/status.h"

namespace tessera::cli {

Expected<BaseMesh> loadMesh(const std::string& path, const std::string* tagsPath, bool triangulate);

}  // namespace tessera::cli
