// The feature-tag parser (core/io/tag_file.h): `--tags FILE` and the tags a
// client sends with CreateDocument. Tags that parse are applied to the
// creased cube (errors are fine, crashes are not), and every parsed
// sharpness must be what parseSharpness accepts: finite and >= 0, or +inf.
#include <cmath>
#include <string>

#include "core/io/tag_file.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  using namespace tessera::fuzz;
  auto tags = parseTags(bytesOf(data, size), "fuzz.tags");
  if (!tags.isOk()) {
    checkError(tags.status(), "parseTags");
    return 0;
  }
  for (const FeatureTag& tag : *tags) {
    require(tag.sharpness >= 0.0f && !std::isnan(tag.sharpness),
            "a parsed tag has a negative or NaN sharpness");
    require(tag.line >= 1, "a parsed tag has no line number");
  }
  BaseMesh mesh = creasedCube();
  checkError(applyTags(*tags, "fuzz.tags", mesh), "applyTags");
  return 0;
}
