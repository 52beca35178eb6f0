// A Catmull-Clark document created from untrusted OBJ bytes, as the server
// creates one for a CreateDocument (server/document/mesh_intake.h): the
// polygon reader with OpenSubdiv's `t` tags (crease, corner,
// interpolateboundary, creasemethod; docs/FORMATS.md), the document's
// checks of the cage, and then the surface those rules give. The input's
// length parity picks whether the scheme is asked for or left to the file
// (a file of triangles only is then a Loop document), so both of the
// server's choices are reached. A document that is created is refined to
// level 2 and its limit surface evaluated; small cages only, so that the
// run stays fast.
#include <string>

#include "fuzz_support.h"
#include "server/document/mesh_intake.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  using namespace tessera::fuzz;
  if (size > 16384) return 0;
  wire::CreateDocument request;
  request.set_name("fuzz");
  request.set_mesh(bytesOf(data, size));
  request.set_mesh_format(wire::MESH_FORMAT_OBJ);
  request.set_max_level(2);
  if (size % 2 == 0) request.set_scheme(wire::SUBDIVISION_SCHEME_CATMULL_CLARK);
  ImportReport report;
  auto doc = server::importDocument(request, 4, report);
  if (!doc.isOk()) {
    checkError(doc.status(), "importDocument");
    return 0;
  }
  if (doc->counts().faces(0) > 256) return 0;  // larger cages only slow the run down
  auto limit = doc->surface(2, SurfaceKind::kLimit);
  if (!limit.isOk()) checkError(limit.status(), "the limit surface of a created document");
  return 0;
}
