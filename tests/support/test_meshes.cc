#include "support/test_meshes.h"

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"

namespace tessera::testing {

std::string cgalMeshPath(const std::string& name) {
  return std::string(TESSERA_TESTDATA_DIR) + "/cgal/" + name;
}

std::string sourceTestDataPath(const std::string& relative) {
  return std::string(TESSERA_SOURCE_TESTDATA_DIR) + "/" + relative;
}

namespace {

// The directories makeTempDir made in this process, removed when it exits
// normally (a crashed test leaves its directory to be looked at).
struct TempDirs {
  std::mutex mutex;
  std::vector<std::string> paths;  // made and not kept
};

TempDirs& tempDirs() {
  static TempDirs* dirs = [] {
    auto* made = new TempDirs;  // never destroyed, so the exit handler never finds it gone
    std::atexit(removeTempDirs);
    return made;
  }();
  return *dirs;
}

}  // namespace

void keepTempDirs(const std::string& why) {
  TempDirs& dirs = tempDirs();
  std::lock_guard lock(dirs.mutex);
  for (const std::string& path : dirs.paths) std::cerr << "kept " << path << ": " << why << "\n";
  dirs.paths.clear();
}

void removeTempDirs() {
  if (const char* keep = std::getenv("TESSERA_KEEP_TEST_DIRS"); keep && *keep && std::string(keep) != "0")
    return;
  TempDirs& dirs = tempDirs();
  std::lock_guard lock(dirs.mutex);
  for (const std::string& path : dirs.paths) {
    std::error_code ignored;  // a server still writing there loses nothing the test needed
    std::filesystem::remove_all(path, ignored);
  }
  dirs.paths.clear();
}

std::string makeTempDir(const std::string& prefix) {
  std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed for " + pattern);
  TempDirs& dirs = tempDirs();
  std::lock_guard lock(dirs.mutex);
  dirs.paths.push_back(pattern);
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
