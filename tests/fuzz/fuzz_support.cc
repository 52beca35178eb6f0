#include "fuzz_support.h"

#include <unistd.h>

#include <filesystem>
#include <map>
#include <memory>

#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"

namespace tessera::fuzz {

const BaseMesh& creasedCube() {
  static const BaseMesh mesh = [] {
    const std::string dir = TESSERA_FUZZ_TESTDATA_DIR;
    auto imported = importMesh(dir + "/cube.obj");
    if (!imported.isOk()) fail("cannot read the cube: " + imported.status().toString());
    Status tagged = applyTagFile(dir + "/cube.tags", *imported);
    if (!tagged.isOk()) fail("cannot tag the cube: " + tagged.toString());
    return std::move(*imported);
  }();
  return mesh;
}

const Document& cubeDocument(int maxLevel) {
  static std::map<int, std::unique_ptr<Document>> documents;
  auto& doc = documents[maxLevel];
  if (!doc) {
    auto created = Document::create(creasedCube(), {.maxLevel = maxLevel});
    if (!created.isOk()) fail("cannot create the cube document: " + created.status().toString());
    doc = std::make_unique<Document>(std::move(*created));
  }
  return *doc;
}

}  // namespace tessera::fuzz
