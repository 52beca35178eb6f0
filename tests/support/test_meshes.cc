#include "support/test_meshes.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"

namespace tessera::testing {

std::string cgalMeshPath(const std::string& name) {
  return std::string(TESSERA_TESTDATA_DIR) + "/cgal/" + name;
}

std::string sourceTestDataPath(const std::string& relative) {
  return std::string(TESSERA_SOURCE_TESTDATA_DIR) + "/" + relative;
}

std::string makeTempDir(const std::string& prefix) {
  std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed for " + pattern);
  return pattern;
}

Expected<BaseMesh> creasedCube() {
  TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, importMesh(sourceTestDataPath("cube.obj")));
  TESSERA_RETURN_IF_ERROR(applyTagFile(sourceTestDataPath("cube.tags"), mesh));
  return mesh;
}

Expected<Document> cubeDocument(int maxLevel) {
  TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, importMesh(sourceTestDataPath("cube.obj")));
  return Document::create(mesh, {.maxLevel = maxLevel});
}

}  // namespace tessera::testing
