// One mesh importer (core/io/mesh_import.h) on untrusted file contents: the
// file a user passes to `tessera` or a client sends with CreateDocument.
// Compiled once per format; TESSERA_FUZZ_EXTENSION (".obj", ".off", ".ply",
// ".stl", ".gltf", ".glb") picks the reader, as the file name does.
//
// importMesh reads files only, so the input is written to a file private to
// the process first. The input's length parity picks ImportOptions::
// triangulate (deterministic per input, so crashes reproduce). A mesh that
// imports is small enough here to become a document: it is refined to level
// 2 and its limit surface evaluated, so that the Loop rules meet whatever
// topology and tags the importers let through.
#include <fstream>
#include <string>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  using namespace tessera::fuzz;
  static const std::string path = scratchPath(TESSERA_FUZZ_EXTENSION);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) fail("cannot write " + path);
  }
  auto mesh = importMesh(path, {.triangulate = size % 2 == 1});
  if (!mesh.isOk()) {
    checkError(mesh.status(), "importMesh");
    require(mesh.status().message().find(path) != std::string::npos, "an import error does not name the file");
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
