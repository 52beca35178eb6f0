#include "client/cli/mesh_loading.h"

#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"

namespace tessera::cli {

Expected<BaseMesh> loadMesh(const std::string& path, const std::string* tagsPath, bool triangulate) {
  ImportOptions options;
  options.triangulate = triangulate;
  TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, importMesh(path, options));
  if (tagsPath != nullptr) TESSERA_RETURN_IF_ERROR(applyTagFile(*tagsPath, mesh));
  return mesh;
}

}  // namespace tessera::cli
