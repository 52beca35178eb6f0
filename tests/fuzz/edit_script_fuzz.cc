// The edit script parser (core/document/edit_script.h), and applying what it
// parses to a creased-cube document of max level kFuzzDocumentLevel: what
// `tessera doc edit --script` and `tessera remote edit` do with a user's
// file. A script applies entirely or not at all, so a refused script must
// leave the document's edits as they were.
#include <string>

#include "core/document/edit_script.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  using namespace tessera::fuzz;
  const std::string text = bytesOf(data, size);
  auto commands = parseEditScript(text, "fuzz.script");
  if (!commands.isOk()) {
    checkError(commands.status(), "parseEditScript");
    return 0;
  }
  Document doc = cubeDocument(kFuzzDocumentLevel);
  auto applied = applyEditScript(text, "fuzz.script", doc);
  if (!applied.isOk()) {
    checkError(applied.status(), "applyEditScript");
    require(doc.edits().empty(), "a refused script left edits in the document");
  }
  return 0;
}
