// One mesh importer (core/io/mesh_import.h) on untrusted file contents: the
// file a user passes to `tessera` or a client sends with CreateDocument.
// Compiled once per format; TESSERA_FUZZ_EXTENSION (".obj", ".off", ".ply",
// ".stl", ".gltf", ".glb", ".usda") picks the reader, as the file name does.
//
// The in-memory entry point (importMeshFromBytes) is what the server runs on
// a CreateDocument's bytes and what importMesh(path) runs after reading the
// file, so no file is written per input. The input's length parity picks ImportOptions::
// triangulate (deterministic per input, so crashes reproduce). A mesh that
// imports is small enough here to become a document: it is refined to level
// 2 and its limit surface evaluated, so that the Loop rules meet whatever
// topology and tags the importers let through.
#include <string>
#include <string_view>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  using namespace tessera::fuzz;
  static const std::string name = std::string("fuzz-input") + TESSERA_FUZZ_EXTENSION;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  auto mesh = importMeshFromBytes(bytes, TESSERA_FUZZ_EXTENSION, name, {.triangulate = size % 2 == 1});
  if (!mesh.isOk()) {
    checkError(mesh.status(), "importMeshFromBytes");
    require(mesh.status().message().find(name) != std::string::npos,
            "an import error does not name the input");
    return 0;
  }
  if (mesh->numFaces() > 256) return 0;  // larger meshes only slow the run down
  auto doc = Document::create(*mesh, {.maxLevel = 2});
  if (!doc.isOk()) {
    checkError(doc.status(), "Document::create of an imported mesh");
    return 0;
  }
  auto limit = doc->surface(2, SurfaceKind::kLimit);
  if (!limit.isOk()) checkError(limit.status(), "the limit surface of an imported mesh");
  return 0;
}
