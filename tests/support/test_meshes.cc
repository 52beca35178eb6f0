#include "support/test_meshes.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

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

}  // namespace tessera::testing
